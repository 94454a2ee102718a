// GCC bug 105616: with -fsanitize=address, GCC 12 reports libstdc++'s std::regex compiler as using
// a std::function member uninitialised (-Wmaybe-uninitialized), a false positive. This translation
// unit holds nothing but the regex searches of the tests, so the warning is silenced here alone.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include "pattern.hpp"

#include <regex>

namespace sc::test {

struct Pattern::Compiled {
  std::regex re;
};

Pattern::Pattern(const std::string& expression) : compiled_(std::make_unique<Compiled>(Compiled{std::regex(expression)})) {}
Pattern::~Pattern() = default;
Pattern::Pattern(Pattern&&) noexcept = default;
Pattern& Pattern::operator=(Pattern&&) noexcept = default;

bool Pattern::found_in(const std::string& text) const { return std::regex_search(text, compiled_->re); }

std::optional<std::vector<std::string>> Pattern::first_in(const std::string& text) const {
  std::smatch m;
  if (!std::regex_search(text, m, compiled_->re)) return std::nullopt;
  std::vector<std::string> groups;
  for (std::size_t g = 1; g < m.size(); ++g) groups.push_back(m[g].str());
  return groups;
}

std::vector<std::string> Pattern::every_in(const std::string& text) const {
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), compiled_->re); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[1].str());
  return out;
}

}  // namespace sc::test
