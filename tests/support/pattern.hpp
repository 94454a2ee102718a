// Regular-expression search for the tests that read the command's output and the sources. Every use
// of std::regex in the tests goes through this class, so that <regex> is compiled in one translation
// unit (tests/support/pattern.cpp): with -fsanitize=address, GCC 12 warns -Wmaybe-uninitialized on
// libstdc++'s regex compiler (GCC bug 105616, a false positive), and that file alone silences it.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sc::test {

/// An ECMAScript regular expression, compiled once.
class Pattern {
 public:
  explicit Pattern(const std::string& expression);
  ~Pattern();
  Pattern(Pattern&&) noexcept;
  Pattern& operator=(Pattern&&) noexcept;

  /// Whether the pattern matches somewhere in `text`.
  bool found_in(const std::string& text) const;
  /// The capture groups (1, 2, ...) of the first match in `text`; nullopt when nothing matches.
  std::optional<std::vector<std::string>> first_in(const std::string& text) const;
  /// Capture group 1 of every match in `text`, in order.
  std::vector<std::string> every_in(const std::string& text) const;

 private:
  struct Compiled;
  std::unique_ptr<Compiled> compiled_;
};

}  // namespace sc::test
