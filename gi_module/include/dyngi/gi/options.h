#pragma once
// Option tables: the one place a setting's name, valid range and one-line help live, beside the
// options struct whose member initializer is its one default. The sample's command line, its --help
// text, the stats JSON ("settings") and a settings panel are all generated from these tables, so a new
// setting is one struct member plus one table row.
//
//   struct MyOptions { uint32_t rays = 8; static const OptionTable<MyOptions>& table(); };
//   const OptionTable<MyOptions>& MyOptions::table() {
//     static const auto t = OptionTable<MyOptions>().add({"rays", "rays per pixel", 1, 64}, &MyOptions::rays);
//     return t;
//   }
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace dyngi::gi {

struct OptionSpec {
  const char* name = "";  // command line --name, stats JSON key, panel label (lower case, dashes)
  const char* help = "";  // one line
  double min = 0, max = 0;  // inclusive valid range (bools: 0..1)
  bool powerOfTwo = false;
};

// A typed pointer into a live options struct.
using OptionValuePtr = std::variant<uint32_t*, uint64_t*, float*, bool*>;

// One option of one live options object: its spec, read and written as a double (exact for every
// integer an option can hold).
struct OptionRef {
  const OptionSpec* spec = nullptr;
  OptionValuePtr value;
  double get() const;
  void set(double v) const;  // the caller checks the range (parseOptionValue)
  bool isBool() const { return std::holds_alternative<bool*>(value); }
  bool isInteger() const { return !std::holds_alternative<float*>(value); }
  std::string text() const;  // the value as the command line writes it
};

template <class S>
class OptionTable {
 public:
  // A direct member, or an accessor for a member of a member (shared sub-structs).
  template <class M>
  OptionTable& add(OptionSpec spec, M S::*member) {
    rows_.push_back({spec, [member](S& s) -> OptionValuePtr { return &(s.*member); }});
    return *this;
  }
  OptionTable& add(OptionSpec spec, std::function<OptionValuePtr(S&)> access) {
    rows_.push_back({spec, std::move(access)});
    return *this;
  }
  // Every row of a sub-struct's table (its S::table()), reached through `member`.
  template <class Sub>
  OptionTable& include(Sub S::*member) {
    for (const auto& row : Sub::table().rows())
      rows_.push_back({row.spec, [member, access = row.access](S& s) { return access(s.*member); }});
    return *this;
  }
  // Every row, pointed at `object`.
  std::vector<OptionRef> bind(S& object) const {
    std::vector<OptionRef> refs;
    for (const Row& r : rows_) refs.push_back({&r.spec, r.access(object)});
    return refs;
  }

  struct Row {
    OptionSpec spec;
    std::function<OptionValuePtr(S&)> access;
  };
  const std::vector<Row>& rows() const { return rows_; }

 private:
  std::vector<Row> rows_;
};

template <class S>
std::vector<OptionRef> bindOptions(S& object) {
  return S::table().bind(object);
}

// Parses `text` for `option` and checks its range; returns an error line ("--vpls wants an integer in
// 16..65536, got '3'") or "" after writing the value.
std::string parseOptionValue(const OptionRef& option, std::string_view text);
// "16..65536", "a power of two in 64..512", "0..1"
std::string describeRange(const OptionRef& option);
// Lines "  --name VALUE   help (default D, range)" for a --help text; `defaults` bound to a
// default-constructed object.
std::string optionHelp(const std::vector<OptionRef>& defaults);
// For each option whose value in `effective` differs from `requested` (same table, two objects): one
// line "--vpls 100 is used as 99".
std::vector<std::string> adjustedOptions(const std::vector<OptionRef>& requested, const std::vector<OptionRef>& effective);

}  // namespace dyngi::gi
