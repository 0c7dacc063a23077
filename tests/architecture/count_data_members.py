#!/usr/bin/env python3
"""Counts the non-static data members of every class, struct and union defined in
C++ files and fails when one has more than the limit (15) without an exception.

    count_data_members.py --exceptions FILE [--limit 15] [--list] DIR...
    (data_members_self_test.py shows it refusing a planted 16-member class)

A data member is a non-static member declaration that is not a function: `int a, b;`
is two, `std::array<int, 3> c{};` one, a nested `struct {...} d;` one for the outer
class (and the nested struct is counted on its own), an anonymous union one. Static
and constexpr members, using-declarations and aliases, typedefs, friends, enums,
static_asserts, member functions (declared or defined, constructors with their
initialiser lists) and forward declarations are not data members. Comments, string
and character literals and preprocessor lines are ignored. Classes defined inside
function bodies are not looked at.

Classes are named by their namespaces and enclosing classes without the leading
`twister::` (`station::StationLink`, `station::StationLink::Handshake`). The
exceptions file has one class a line: `NAME  COUNT  reason...` (# comments). COUNT
is the most members that class may have. The check fails for a class over the limit
that is not listed, a listed class that grew past its COUNT, and a listed class that
is no longer over the limit or no longer exists (delete its line: the list only
shrinks).
"""

import argparse
import os
import re
import sys

DEFAULT_LIMIT = 15
EXTENSIONS = (".hpp", ".h", ".cpp", ".cc")


def clean(text):
    """Blanks comments, string and character literals and preprocessor lines; keeps
    newlines so offsets map to the same lines."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in " \t":
            out.append(c)
            i += 1
            continue
        if line_start and c == "#":
            # A preprocessor directive, with its continuation lines.
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append(" \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        line_start = False
        if c == "\n":
            line_start = True
            out.append(c)
            i += 1
        elif text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not _ident(text[i - 1])):
            m = re.compile(r'R"([^(\s]*)\(').match(text, i)
            if not m:
                out.append(c)
                i += 1
                continue
            close = ")" + m.group(1) + '"'
            end = text.find(close, m.end())
            end = n if end < 0 else end + len(close)
            out.append('""' + re.sub(r"[^\n]", " ", text[i + 2 : end]))
            i = end
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum())):
            # A literal (a ' between two alphanumerics is a digit separator: 1'000).
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j, n) - i - 1) + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def _ident(ch):
    return ch.isalnum() or ch == "_"


# --- Matching brackets -------------------------------------------------------------

_PAIRS = {"(": ")", "[": "]", "{": "}"}


def matching(s, i):
    """Index of the bracket closing the one at s[i] (nested (), [], {} balanced)."""
    stack = [_PAIRS[s[i]]]
    j = i + 1
    while j < len(s):
        ch = s[j]
        if ch in _PAIRS:
            stack.append(_PAIRS[ch])
        elif ch in ")]}":
            if stack and ch == stack[-1]:
                stack.pop()
                if not stack:
                    return j
        j += 1
    return len(s) - 1


def strip_angles(s):
    """Removes template argument lists: a `<` right after an identifier (clang-format
    puts none between a template name and its arguments; a `<` operator has
    spaces) up to its `>`."""
    out = []
    depth = 0
    for k, ch in enumerate(s):
        if ch == "<" and (depth > 0 or (k > 0 and (_ident(s[k - 1]) or s[k - 1] == ">"))):
            if k + 1 < len(s) and s[k + 1] == "<" and depth == 0:
                out.append(ch)  # << operator
                continue
            depth += 1
            continue
        if ch == ">" and depth > 0:
            depth -= 1
            continue
        if depth == 0:
            out.append(ch)
    return "".join(out)


def strip_balanced(s, opener_regex):
    """Removes every `<keyword>(...)` matched by opener_regex (ending at the `(`)."""
    while True:
        m = re.search(opener_regex, s)
        if not m:
            return s
        start = m.end() - 1
        end = matching(s, start)
        s = s[: m.start()] + " " + s[end + 1 :]


def depth0_split(s, sep):
    """Splits s at `sep` characters outside (), [], {} and template arguments."""
    s = strip_angles(s)
    parts, depth, cur = [], 0, []
    for ch in s:
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        if ch == sep and depth == 0:
            parts.append("".join(cur))
            cur = []
        else:
            cur.append(ch)
    parts.append("".join(cur))
    return parts


# --- Declarations ------------------------------------------------------------------

ACCESS = re.compile(r"^\s*(?:(?:public|private|protected)\s*:(?!:)\s*)+")
ATTRIBUTES = re.compile(r"\[\[.*?\]\]", re.S)
TEMPLATE_HEAD = re.compile(r"^\s*template\s*<")
TYPE_HEAD = re.compile(
    r"^(?:class|struct|union)\s*(?:alignas\s*\([^)]*\)\s*)?(?P<name>[A-Za-z_]\w*(?:\s*::\s*[A-Za-z_]\w*)*)?"
    r"\s*(?:final\s*)?(?::(?!:)[^{;]*)?$",
    re.S,
)
SKIP_WORDS = re.compile(r"^\s*(?:using|typedef|friend|static_assert|template|enum|namespace|extern|operator)\b")


def normalize(head):
    head = ATTRIBUTES.sub(" ", head)
    head = ACCESS.sub("", head)
    return " ".join(head.split())


def drop_template_head(head):
    """`template <...> struct X` -> `struct X`."""
    m = TEMPLATE_HEAD.match(head)
    if not m:
        return head
    depth = 0
    for k in range(m.end() - 1, len(head)):
        if head[k] == "<":
            depth += 1
        elif head[k] == ">":
            depth -= 1
            if depth == 0:
                return head[k + 1 :].strip()
    return head


def is_function(head):
    """A member or namespace-scope function: a `(` before any `=` once template
    arguments, alignas/decltype/noexcept(...) and function-pointer declarators are
    set aside."""
    h = drop_template_head(head)
    h = strip_balanced(h, r"\b(?:alignas|decltype|__attribute__)\s*\(")
    h = strip_angles(h)
    h = re.sub(r"\(\s*\*\s*[A-Za-z_]\w*\s*\)\s*\(", "FNPTR(", h)  # void (*f)(int): data
    prefix = depth0_split(h, "=")[0]
    prefix = prefix.replace("FNPTR(", "FNPTR ")
    return "(" in prefix or re.search(r"\boperator\b", prefix) is not None


def declarator_count(decl):
    """Declarators in a member declaration: depth-0 commas + 1."""
    return len([p for p in depth0_split(decl, ",") if p.strip()])


def member_declaration(stmt):
    """How many data members a class-scope statement (no body) declares."""
    s = normalize(stmt)
    if not s:
        return 0
    if SKIP_WORDS.match(s):
        return 0
    specifiers = depth0_split(s, "=")[0]
    specifiers = re.split(r"[{]", specifiers)[0]
    if re.search(r"\b(?:static|constexpr|consteval|typedef)\b", specifiers):
        return 0
    if is_function(s):
        return 0
    if re.fullmatch(r"(?:class|struct|union)\s+[A-Za-z_][\w:]*", s):
        return 0  # a forward declaration
    return declarator_count(s)


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def scan_scope(src, begin, end, kind, name, path, found):
    """Scans src[begin:end] (a namespace or class body named `name`), appending
    (qualified name, members, path, line) of each class to `found`. Returns the
    data members when `kind` is "class"."""
    members = 0
    stmt = begin
    i = begin
    while i < end:
        ch = src[i]
        if ch == ";":
            if kind == "class":
                members += member_declaration(src[stmt:i])
            stmt = i + 1
        elif ch in "([":
            i = matching(src, i)
        elif ch == "{":
            close = min(matching(src, i), end)
            head = normalize(src[stmt:i])
            bare = drop_template_head(head)
            if re.match(r"^(?:inline\s+)?namespace\b|^extern\s*\"", head):
                m = re.match(r"^(?:inline\s+)?namespace\s*([\w:]*)", head)
                inner = m.group(1) if m and m.group(1) else "(anonymous)"
                scan_scope(src, i + 1, close, "namespace", qualify(name, inner), path, found)
                stmt = close + 1
                i = close
            elif re.match(r"^(?:class|struct|union)\b", bare) and TYPE_HEAD.match(bare):
                type_name = TYPE_HEAD.match(bare).group("name")
                type_name = re.sub(r"\s+", "", type_name) if type_name else "(anonymous)"
                qualified = qualify(name, type_name)
                count = scan_scope(src, i + 1, close, "class", qualified, path, found)
                found.append((qualified, count, path, line_of(src, i)))
                # What follows the body up to `;`: declarators of the outer class.
                semi = src.find(";", close)
                semi = end if semi < 0 or semi > end else semi
                tail = normalize(src[close + 1 : semi])
                if kind == "class":
                    if tail:
                        members += declarator_count(tail)
                    elif type_name == "(anonymous)":
                        members += 1  # an anonymous union or struct
                stmt = semi + 1
                i = semi
            elif re.match(r"^(?:\w+\s+)*enum\b", head):
                i = close  # an enumeration's body: the statement goes on to its `;`
            elif is_function(head):
                if ctor_initialiser(head) and (_ident(head[-1:]) or head.endswith(">")):
                    i = close  # a member's brace initialiser in the constructor's list
                else:
                    stmt = close + 1  # the function's body: the declaration is complete
                    i = close
            else:
                i = close  # a brace initialiser: the statement goes on to its `;`
        i += 1
    return members


def ctor_initialiser(head):
    h = strip_angles(head)
    return re.search(r"\)\s*(?:noexcept\s*)?:(?!:)", h) is not None


def qualify(outer, inner):
    return outer + "::" + inner if outer else inner


def display_name(qualified):
    return qualified[len("twister::") :] if qualified.startswith("twister::") else qualified


def scan_file(path, found):
    with open(path, encoding="utf-8", errors="replace") as f:
        src = clean(f.read())
    scan_scope(src, 0, len(src), "namespace", "", path, found)


def scan_tree(roots):
    """[(qualified name, data members, path, line)] of every class under `roots`."""
    found = []
    for root in roots:
        walk = [(os.path.dirname(root), [], [os.path.basename(root)])] if os.path.isfile(root) else []
        for dirpath, dirnames, filenames in walk or os.walk(root):
            dirnames.sort()
            for fn in sorted(f for f in filenames if f.endswith(EXTENSIONS)):
                scan_file(os.path.join(dirpath, fn), found)
    return found


def read_exceptions(path):
    allowed = {}
    problems = []
    with open(path, encoding="utf-8") as f:
        for number, raw in enumerate(f, 1):
            line = raw.split("#", 1)[0].strip()
            if not line:
                continue
            parts = line.split(None, 2)
            if len(parts) < 3 or not parts[1].isdigit():
                problems.append(f"{path}:{number}: expected `NAME COUNT reason`, got: {raw.strip()}")
                continue
            allowed[parts[0]] = (int(parts[1]), parts[2], number)
    return allowed, problems


def check(roots, exceptions_path, limit, listing=False, out=sys.stdout):
    found = scan_tree(roots)
    allowed, problems = read_exceptions(exceptions_path) if exceptions_path else ({}, [])
    largest = {}
    where = {}
    for qualified, count, path, line in found:
        name = display_name(qualified)
        if count >= largest.get(name, -1):
            largest[name] = count
            where[name] = f"{path}:{line}"
    over = {n: c for n, c in largest.items() if c > limit}
    for name in sorted(over):
        if name not in allowed:
            problems.append(
                f"{where[name]}: {name} has {over[name]} data members (limit {limit}); split it, "
                f"or name it in {exceptions_path or 'the exceptions file'} with a reason"
            )
        elif over[name] > allowed[name][0]:
            problems.append(
                f"{where[name]}: {name} has {over[name]} data members, more than the "
                f"{allowed[name][0]} its exception allows ({exceptions_path}:{allowed[name][2]})"
            )
    for name, (count, reason, number) in sorted(allowed.items()):
        if name not in over:
            now = largest.get(name)
            state = "no longer exists" if now is None else f"has {now} data members now"
            problems.append(
                f"{exceptions_path}:{number}: {name} {state} (limit {limit}): delete its exception"
            )
    if listing:
        for name in sorted(over, key=lambda n: (-over[n], n)):
            print(f"{name:50} {over[name]:3}  {where[name]}", file=out)
    for p in problems:
        print(f"data members: {p}", file=out)
    if not problems:
        print(f"data members: {len(found)} classes, none over {limit} but the {len(allowed)} "
              "named exceptions", file=out)
    return 1 if problems else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("roots", nargs="+", help="folders or files to scan")
    ap.add_argument("--exceptions", help="NAME COUNT reason, one class a line")
    ap.add_argument("--limit", type=int, default=DEFAULT_LIMIT)
    ap.add_argument("--list", action="store_true", help="print every class over the limit")
    args = ap.parse_args()
    return check(args.roots, args.exceptions, args.limit, args.list)


if __name__ == "__main__":
    sys.exit(main())
