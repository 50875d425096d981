#include "dyngi/gi/options.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace dyngi::gi {

double OptionRef::get() const {
  return std::visit([](auto* p) { return double(*p); }, value);
}

void OptionRef::set(double v) const {
  std::visit(
      [v](auto* p) {
        using T = std::remove_pointer_t<decltype(p)>;
        if constexpr (std::is_same_v<T, bool>) *p = v != 0.0;
        else *p = T(v);
      },
      value);
}

namespace {
std::string number(double v, bool integer) {
  char buf[64];
  if (integer) std::snprintf(buf, sizeof buf, "%.0f", v);
  else std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace

std::string OptionRef::text() const {
  if (isBool()) return get() != 0.0 ? "on" : "off";
  return number(get(), isInteger());
}

std::string describeRange(const OptionRef& o) {
  if (o.isBool()) return "on|off";
  std::string range = number(o.spec->min, o.isInteger()) + ".." + number(o.spec->max, o.isInteger());
  return o.spec->powerOfTwo ? "a power of two in " + range : range;
}

std::string parseOptionValue(const OptionRef& o, std::string_view text) {
  const std::string flag = std::string("--") + o.spec->name;
  if (o.isBool()) {
    if (text == "on" || text == "1" || text == "true") return o.set(1.0), "";
    if (text == "off" || text == "0" || text == "false") return o.set(0.0), "";
    return flag + " wants on or off, got '" + std::string(text) + "'";
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
    return flag + " wants " + (o.isInteger() && !o.spec->powerOfTwo ? "an integer in " : o.isInteger() ? "" : "a number in ") +
           describeRange(o) + ", got '" + std::string(text) + "'";
  o.set(v);
  return {};
}

std::string optionHelp(const std::vector<OptionRef>& defaults) {
  std::string out;
  for (const OptionRef& o : defaults) {
    std::string flag = std::string("  --") + o.spec->name + (o.isBool() ? " on|off" : o.isInteger() ? " N" : " X");
    if (flag.size() < 41) flag.resize(41, ' ');
    else flag += ' ';
    out += flag + o.spec->help + " (default " + o.text() + (o.isBool() ? "" : ", " + describeRange(o)) + ")\n";
  }
  return out;
}

std::vector<std::string> adjustedOptions(const std::vector<OptionRef>& requested, const std::vector<OptionRef>& effective) {
  std::vector<std::string> lines;
  for (size_t i = 0; i < requested.size() && i < effective.size(); ++i)
    if (requested[i].get() != effective[i].get())
      lines.push_back(std::string("--") + requested[i].spec->name + " " + requested[i].text() + " is used as " + effective[i].text());
  return lines;
}

}  // namespace dyngi::gi
