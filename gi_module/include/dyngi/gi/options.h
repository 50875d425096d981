#pragma once
// Option tables: the one place a setting's valid range and one-line help live, beside the options
// struct whose member initializer is its one default. A setting's name is its member's name: the flag
// `--vpls` is `VplOptions::vpls`, `--temporal-sets` is `TemporalOptions::temporalSets` (camelCase to
// dashes, after the table's prefix when it has one: `VoxelSettings::resolution` is `--voxel-resolution`).
// The sample's command line, its --help, docs/OPTIONS.md, the stats JSON ("settings") and the settings
// panel are all generated from these tables, so a new setting is one struct member plus one table row.
//
//   struct MyOptions { uint32_t rays = 8; static const OptionTable<MyOptions>& table(); };
//   const OptionTable<MyOptions>& MyOptions::table() {
//     static const auto t = OptionTable<MyOptions>().add(DYNGI_OPTION(MyOptions, rays), "rays per pixel", 1, 64);
//     return t;
//   }
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

// A member and its name, for OptionTable::add / addChoice: the name becomes the option's flag.
#define DYNGI_OPTION(Struct, member) #member, &Struct::member

namespace dyngi::gi {

// "temporalSets" -> "temporal-sets"; with a prefix "voxel", "resolution" -> "voxel-resolution".
std::string optionName(std::string_view prefix, std::string_view member);

struct OptionSpec {
  std::string name;                  // --name, stats JSON key, panel label: the member's name with dashes
  const char* help = "";             // one line
  double min = 0, max = 0;           // inclusive valid range (bools: 0..1; choices: 0..count - 1)
  bool powerOfTwo = false;
  std::vector<const char*> choices;      // an enum's values by name; empty otherwise
  std::vector<uint32_t> choiceValues;    // the enum value of each name
};

// A named-value option (an enum member): its raw enum value.
struct ChoicePtr {
  void* object = nullptr;
  uint32_t (*read)(const void*) = nullptr;
  void (*write)(void*, uint32_t) = nullptr;
};

// A typed pointer into a live options struct.
using OptionValuePtr = std::variant<uint32_t*, uint64_t*, float*, bool*, ChoicePtr>;

// One option of one live options object: its spec, read and written as a double (exact for every
// integer an option can hold; a choice's index).
struct OptionRef {
  const OptionSpec* spec = nullptr;
  OptionValuePtr value;
  double get() const;
  void set(double v) const;  // the caller checks the range (parseOptionValue)
  bool isBool() const { return std::holds_alternative<bool*>(value); }
  bool isChoice() const { return std::holds_alternative<ChoicePtr>(value); }
  bool isInteger() const { return !std::holds_alternative<float*>(value); }
  std::string text() const;  // the value as the command line writes it
  std::string flag() const { return "--" + spec->name; }
};

template <class S>
class OptionTable {
 public:
  // `prefix` leads every name of this table's own rows ("voxel": --voxel-resolution).
  explicit OptionTable(std::string prefix = {}) : prefix_(std::move(prefix)) {}

  // A number or bool member: add(DYNGI_OPTION(S, member), help, min, max[, powerOfTwo]).
  template <class M>
  OptionTable& add(const char* member, M S::*field, const char* help, double min, double max, bool powerOfTwo = false) {
    rows_.push_back({OptionSpec{optionName(prefix_, member), help, min, max, powerOfTwo, {}},
                     [field](S& s) -> OptionValuePtr { return &(s.*field); }});
    return *this;
  }
  // An enum member and the values it may take by name ({"svo", Visibility::Svo}, ...).
  template <class E>
  OptionTable& addChoice(const char* member, E S::*field, const char* help, std::vector<std::pair<const char*, E>> choices) {
    OptionSpec spec{optionName(prefix_, member), help, 0, double(choices.size()) - 1, false, {}, {}};
    for (const auto& [name, v] : choices) spec.choices.push_back(name), spec.choiceValues.push_back(uint32_t(v));
    rows_.push_back({std::move(spec),
                     [field](S& s) -> OptionValuePtr {
                       return ChoicePtr{&(s.*field), [](const void* p) { return uint32_t(*static_cast<const E*>(p)); },
                                        [](void* p, uint32_t v) { *static_cast<E*>(p) = E(v); }};
                     }});
    return *this;
  }
  // Every row of a sub-struct's table (its S::table()), reached through `member`, under their own names.
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
  std::string prefix_;
  std::vector<Row> rows_;
};

template <class S>
std::vector<OptionRef> bindOptions(S& object) {
  return S::table().bind(object);
}

// The option named `name` in `options` (a copy: it points into the options object, not the vector).
std::optional<OptionRef> findOption(const std::vector<OptionRef>& options, std::string_view name);
// Parses `text` for `option` and checks its range; returns an error line ("--vpls wants an integer in
// 16..65536, got '3'") or "" after writing the value.
std::string parseOptionValue(const OptionRef& option, std::string_view text);
// "16..65536", "a power of two in 64..512", "on|off", "svo|bvh"
std::string describeRange(const OptionRef& option);
// Lines "  --name VALUE   help (default D, range)" for a --help text; `defaults` bound to a
// default-constructed object.
std::string optionHelp(const std::vector<OptionRef>& defaults);
// Rows "| `--name VALUE` | default | range | help |" of a Markdown table (docs/OPTIONS.md).
std::string optionMarkdown(const std::vector<OptionRef>& defaults);
// For each option whose value in `effective` differs from `requested` (same table, two objects): one
// line "--vpls 100 is used as 99".
std::vector<std::string> adjustedOptions(const std::vector<OptionRef>& requested, const std::vector<OptionRef>& effective);

}  // namespace dyngi::gi
