#include "dyngi/gi/options.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace dyngi::gi {

std::string optionName(std::string_view prefix, std::string_view member) {
  std::string name(prefix);
  if (!name.empty()) name += '-';
  for (char c : member) {
    if (std::isupper(static_cast<unsigned char>(c))) {
      name += '-';
      name += char(std::tolower(static_cast<unsigned char>(c)));
    } else {
      name += c;
    }
  }
  return name;
}

namespace {
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

std::string number(double v, bool integer) {
  char buf[64];
  if (integer) std::snprintf(buf, sizeof buf, "%.0f", v);
  else std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string choiceList(const OptionSpec& spec, const char* separator) {
  std::string list;
  for (const char* c : spec.choices) list += (list.empty() ? "" : separator) + std::string(c);
  return list;
}
}  // namespace

double OptionRef::get() const {
  return std::visit(Overloaded{[this](const ChoicePtr& c) {
                                 const uint32_t raw = c.read(c.object);
                                 for (size_t i = 0; i < spec->choiceValues.size(); ++i)
                                   if (spec->choiceValues[i] == raw) return double(i);
                                 return -1.0;  // a value the table does not name
                               },
                               [](auto* p) { return double(*p); }},
                    value);
}

void OptionRef::set(double v) const {
  std::visit(Overloaded{[this, v](const ChoicePtr& c) { c.write(c.object, spec->choiceValues.at(size_t(v))); },
                        [v](auto* p) {
                          using T = std::remove_pointer_t<decltype(p)>;
                          if constexpr (std::is_same_v<T, bool>) *p = v != 0.0;
                          else *p = T(v);
                        }},
             value);
}

std::string OptionRef::text() const {
  if (isBool()) return get() != 0.0 ? "on" : "off";
  if (isChoice()) {
    const double i = get();
    return i >= 0 ? spec->choices[size_t(i)] : "?";
  }
  return number(get(), isInteger());
}

std::optional<OptionRef> findOption(const std::vector<OptionRef>& options, std::string_view name) {
  for (const OptionRef& o : options)
    if (o.spec->name == name) return o;
  return std::nullopt;
}

std::string describeRange(const OptionRef& o) {
  if (o.isBool()) return "on|off";
  if (o.isChoice()) return choiceList(*o.spec, "|");
  std::string range = number(o.spec->min, o.isInteger()) + ".." + number(o.spec->max, o.isInteger());
  return o.spec->powerOfTwo ? "a power of two in " + range : range;
}

namespace {
std::string parseChoice(const OptionRef& o, std::string_view text) {
  for (size_t i = 0; i < o.spec->choices.size(); ++i)
    if (text == o.spec->choices[i]) return o.set(double(i)), "";
  return o.flag() + " wants one of " + choiceList(*o.spec, ", ") + ", got '" + std::string(text) + "'";
}
}  // namespace

std::string parseOptionValue(const OptionRef& o, std::string_view text) {
  if (o.isChoice()) return parseChoice(o, text);
  if (o.isBool()) {
    if (text == "on" || text == "1" || text == "true") return o.set(1.0), "";
    if (text == "off" || text == "0" || text == "false") return o.set(0.0), "";
    return o.flag() + " wants on or off, got '" + std::string(text) + "'";
  }
  double v = 0;
  bool ok = false;
  if (o.isInteger()) {
    uint64_t n = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), n);
    ok = r.ec == std::errc() && r.ptr == text.data() + text.size();
    v = double(n);
  } else {
    float f = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), f);
    ok = r.ec == std::errc() && r.ptr == text.data() + text.size() && std::isfinite(f);
    v = double(f);
  }
  const bool pow2 = !o.spec->powerOfTwo || (v >= 1 && (uint64_t(v) & (uint64_t(v) - 1)) == 0);
  if (!ok || v < o.spec->min || v > o.spec->max || !pow2)
    return o.flag() + " wants " + (o.isInteger() && !o.spec->powerOfTwo ? "an integer in " : o.isInteger() ? "" : "a number in ") +
           describeRange(o) + ", got '" + std::string(text) + "'";
  o.set(v);
  return {};
}

namespace {
const char* metavar(const OptionRef& o) {
  return o.isBool() ? "on|off" : o.isChoice() ? "NAME" : o.isInteger() ? "N" : "X";
}
}  // namespace

std::string optionHelp(const std::vector<OptionRef>& defaults) {
  std::string out;
  for (const OptionRef& o : defaults) {
    std::string flag = "  " + o.flag() + " " + (o.isChoice() ? describeRange(o) : metavar(o));
    if (flag.size() < 41) flag.resize(41, ' ');
    else flag += ' ';
    const bool showRange = !o.isBool() && !o.isChoice();
    out += flag + o.spec->help + " (default " + o.text() + (showRange ? ", " + describeRange(o) : "") + ")\n";
  }
  return out;
}

namespace {
std::string markdownCell(std::string_view text) {
  std::string cell;
  for (char c : text) cell += c == '|' ? std::string("\\|") : std::string(1, c);
  return cell;
}
}  // namespace

std::string optionMarkdown(const std::vector<OptionRef>& defaults) {
  std::string out;
  for (const OptionRef& o : defaults)
    out += "| `" + o.flag() + "` | " + markdownCell(o.text()) + " | " + markdownCell(describeRange(o)) + " | " + markdownCell(o.spec->help) + " |\n";
  return out;
}

std::vector<std::string> adjustedOptions(const std::vector<OptionRef>& requested, const std::vector<OptionRef>& effective) {
  std::vector<std::string> lines;
  for (size_t i = 0; i < requested.size() && i < effective.size(); ++i)
    if (requested[i].get() != effective[i].get())
      lines.push_back(requested[i].flag() + " " + requested[i].text() + " is used as " + effective[i].text());
  return lines;
}

}  // namespace dyngi::gi
