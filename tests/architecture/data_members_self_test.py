#!/usr/bin/env python3
"""Self-test of count_data_members.py: a planted header with a 16-member class
written with every construct the counter must see through (comments, literals,
preprocessor lines, multi-line declarations, brace and default initialisers,
constructor initialiser lists, nested and anonymous types, static and constexpr
members, functions) must be refused without an exception, and a 15-member class
passed; the exceptions file's rules (grew past its count, back within the limit,
gone) each fail. So the check cannot pass vacuously."""

import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from count_data_members import DEFAULT_LIMIT, check, display_name, scan_tree  # noqa: E402

PLANTED = r'''
// A header the way core writes them, with what the counter must see through.
#pragma once
#include <array>
#define TWISTER_SOMETHING(x) \
  int macro_member_##x;   /* a preprocessor line: not code */
namespace twister::probe {
class Planted final : public Base<int, 2> {  // 16 data members
 public:
  static constexpr int kLimit = 15;          // static: not counted
  static inline std::array<int, 2> table{1, 2};
  using Alias = std::array<int, 3>;
  enum class Kind : std::uint8_t { a, b };
  struct Inner {                              // counted on its own: 2
    int x = 0;
    float y{1.0F};
  };
  Planted(int a, int b) : a_(a), b_{b}, c_{} { go(); }
  Planted(const Planted&) = delete;
  ~Planted() override;
  int get() const { return a_; }             // a member function with a body
  template <typename T>
  T as() const {
    return T{a_};
  }
  bool operator==(const Planted&) const = default;
  friend class Other;
  static_assert(sizeof(int) == 4, "a; b");

 private:
  int a_, b_;                                 // 2
  int c_{};                                   // 3
  std::array<std::pair<int, int>, 4> pairs_{};  // 4
  std::map<int, std::vector<int>> map_ = {{1, {2, 3}}};  // 5
  const char* text_ = "x; y { z";            // 6
  char quote_ = '{';                          // 7
  std::uint32_t big_ = 1'000'000;             // 8
  void (*callback_)(int) = nullptr;           // 9
  std::function<void(int)> handler_ = [](int v) { (void)v; };  // 10
  unsigned flags_ : 3;                        // 11
  class SceneView* view_ = nullptr;           // 12
  Inner inner_;                               // 13
  struct {
    int p, q;
  } anonymous_pair_;                          // 14
  union {
    int i;
    float f;
  };                                          // 15
  alignas(16) float aligned_[4] = {0, 0, 0,
                                   0};        // 16, over two lines
  /* int commented_out_; */
  // int also_commented_;
};
struct Fifteen {
  int m1, m2, m3, m4, m5;
  int m6 = 1, m7 = (2 + 3), m8{4};
  std::array<int, 2> m9{}, m10;
  double m11, m12, m13, m14;
  bool m15 = true;
  void f(int a, int b);
};
}  // namespace twister::probe
'''


def self_test():
    failures = []

    def expect(cond, what):
        if not cond:
            failures.append(what)

    with tempfile.TemporaryDirectory() as tmp:
        header = os.path.join(tmp, "planted.hpp")
        with open(header, "w", encoding="utf-8") as f:
            f.write(PLANTED)
        counts = {display_name(q): c for q, c, _, _ in scan_tree([tmp])}
        expect(counts.get("probe::Planted") == 16, f"Planted counted {counts.get('probe::Planted')}, not 16")
        expect(counts.get("probe::Planted::Inner") == 2, f"Inner counted {counts.get('probe::Planted::Inner')}, not 2")
        expect(counts.get("probe::Fifteen") == 15, f"Fifteen counted {counts.get('probe::Fifteen')}, not 15")

        def run(exceptions_text):
            path = os.path.join(tmp, "exceptions.txt")
            with open(path, "w", encoding="utf-8") as f:
                f.write(exceptions_text)
            sink = open(os.path.join(tmp, "out.txt"), "w+", encoding="utf-8")
            rc = check([header], path, DEFAULT_LIMIT, out=sink)
            sink.seek(0)
            text = sink.read()
            sink.close()
            return rc, text

        rc, text = run("# none\n")
        expect(rc == 1 and "probe::Planted has 16 data members" in text,
               f"a 16-member class without an exception passed:\n{text}")
        expect("Fifteen" not in text, f"a 15-member class was refused:\n{text}")
        rc, text = run("probe::Planted 16 being split\n")
        expect(rc == 0, f"a listed 16-member class failed:\n{text}")
        rc, text = run("probe::Planted 15 being split\n")
        expect(rc == 1 and "more than the 15" in text, f"a class past its exception passed:\n{text}")
        rc, text = run("probe::Planted 16 being split\nprobe::Fifteen 15 split already\n")
        expect(rc == 1 and "probe::Fifteen has 15 data members now" in text,
               f"an exception for a class within the limit passed:\n{text}")
        rc, text = run("probe::Planted 16 being split\nprobe::Gone 20 removed\n")
        expect(rc == 1 and "probe::Gone no longer exists" in text,
               f"an exception for a missing class passed:\n{text}")
    for f in failures:
        print(f"data members self-test: {f}")
    if not failures:
        print("data members self-test: the planted 16-member class is refused, the rest as expected")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(self_test())
