#!/usr/bin/env python3
"""Checks the size rules of the developers' guide on src/: no function over 120 lines, no file over
600 lines. Prints one line per breach (file, function, length) and exits 1 when there is any.

Functions are found by brace matching on the code with comments, strings and character literals
blanked out: a brace opened at namespace or class level after a parenthesised parameter list opens a
function body; its length counts from the line of the function's name to its closing brace.

    scripts/check_sizes.py [--root DIR]   check DIR/src (default: the repository of this script)
    scripts/check_sizes.py --self-test    show that the checker flags a long function and a long file
"""
import argparse
import pathlib
import re
import sys

MAX_FUNCTION_LINES = 120
MAX_FILE_LINES = 600

# Nothing is over the limits: an entry here names a file or function allowed to be, with why.
ALLOWED = {}

SCOPE_KEYWORDS = re.compile(r"\b(namespace|class|struct|enum|union)\b[^;(){}]*$|extern\s*\"C\"\s*$")
NAME_BEFORE_PARAMETERS = re.compile(r"((?:[A-Za-z_~][A-Za-z_0-9]*\s*::\s*)*(?:operator\s*[^\s(]+|~?[A-Za-z_][A-Za-z_0-9]*))\s*$")


def blank_comments_and_literals(text):
    """The text with comments, strings and character literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i)
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator 1'000
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(text):
    """(name, first line, line count) of every function body at namespace or class level."""
    code = blank_comments_and_literals(text)
    line_of = [0] * (len(code) + 1)
    line = 1
    for i, c in enumerate(code):
        line_of[i] = line
        if c == "\n":
            line += 1
    found = []
    stack = []  # "scope" (namespace, class, ...), "function" or "other" per open brace
    header_start = 0
    i = 0
    while i < len(code):
        c = code[i]
        if c in ";}":
            if c == "}" and stack:
                kind = stack.pop()
                if kind[0] == "function":
                    found.append((kind[1], kind[2], line_of[i] - kind[2] + 1))
            header_start = i + 1
        elif c == "{":
            header = code[header_start:i]
            in_function = any(k[0] != "scope" for k in stack)
            if in_function:
                stack.append(("other",))
                header_start = i + 1
            elif SCOPE_KEYWORDS.search(" ".join(header.split())):
                stack.append(("scope",))
                header_start = i + 1
            elif "(" in header and re.search(r"\)\s*:", header) and re.search(r"[A-Za-z_0-9>]\s*$", header) \
                    and not re.search(r"\b(const|override|final|noexcept|mutable)\s*$", header):
                # A brace initialiser in a constructor's member initialiser list: skip it.
                depth, j = 0, i
                while j < len(code):
                    depth += code[j] == "{"
                    depth -= code[j] == "}"
                    if depth == 0:
                        break
                    j += 1
                i = j + 1
                continue
            elif "(" in header and ")" in header and "=" not in header.split("(")[0]:
                paren = header.index("(")
                m = NAME_BEFORE_PARAMETERS.search(header[:paren])
                name = m.group(1).replace(" ", "") if m else "?"
                stack.append(("function", name, line_of[header_start + paren]))
                header_start = i + 1
            else:
                stack.append(("other",) if header.strip().endswith(("=", ",", "(", "return")) or header.strip() == ""
                             else ("other",))
                header_start = i + 1
        i += 1
    return found


def check(root, stale=None):
    """The breaches of the rules outside ALLOWED; entries of ALLOWED no longer over go to `stale`."""
    breaches = []
    over = set()
    for path in sorted((root / "src").rglob("*")):
        if path.suffix not in (".cpp", ".h", ".hpp", ".cc") or not path.is_file():
            continue
        relative = path.relative_to(root).as_posix()
        text = path.read_text(encoding="utf-8", errors="replace")
        lines = text.count("\n") + (0 if text.endswith("\n") or not text else 1)
        if lines > MAX_FILE_LINES:
            over.add(relative)
        if lines > MAX_FILE_LINES and relative not in ALLOWED:
            breaches.append(f"{relative}: file is {lines} lines (limit {MAX_FILE_LINES})")
        for name, first, length in functions(text):
            if length > MAX_FUNCTION_LINES:
                over.add(f"{relative}:{name}")
            if length > MAX_FUNCTION_LINES and f"{relative}:{name}" not in ALLOWED:
                breaches.append(f"{relative}:{first}: function {name} is {length} lines (limit {MAX_FUNCTION_LINES})")
    if stale is not None:
        stale.extend(sorted(set(ALLOWED) - over))
    return breaches


def self_test():
    """The checker must be able to fail: a long function and a long file are flagged, by name."""
    import tempfile
    body = "\n".join(f"  x += {k};" for k in range(MAX_FUNCTION_LINES))
    sample = ("namespace a {\nstruct S { int f() const { return 1; } };\n"
              "Foo::Foo(int v) : v_{v}, w_(\"{\") {\n  int x = '}';\n" + body + "\n}\n"
              "int short_one() {\n  return 2;\n}\n}  // namespace a\n")
    found = {name: length for name, _, length in functions(sample)}
    assert found.get("Foo::Foo") == MAX_FUNCTION_LINES + 3, found
    assert found.get("short_one") == 3 and found.get("f") == 1, found
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "src" / "m").mkdir(parents=True)
        (root / "src" / "m" / "long.cpp").write_text(sample + "\n" * MAX_FILE_LINES)
        breaches = check(root)
    assert any("src/m/long.cpp:3: function Foo::Foo is 123 lines" in b for b in breaches), breaches
    assert any("src/m/long.cpp: file is" in b for b in breaches), breaches
    assert len(breaches) == 2, breaches
    print("check_sizes.py self-test: a long function and a long file are flagged")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", type=pathlib.Path, default=pathlib.Path(__file__).resolve().parent.parent)
    parser.add_argument("--self-test", action="store_true")
    args = parser.parse_args()
    if args.self_test:
        self_test()
        return 0
    stale = []
    breaches = check(args.root, stale)
    for entry in stale:
        print(f"check_sizes.py: {entry} is no longer over the limits: remove it from ALLOWED")
    for breach in breaches:
        print(breach)
    if breaches:
        print(f"check_sizes.py: {len(breaches)} over the limits (no function in src/ over {MAX_FUNCTION_LINES} "
              f"lines, no file over {MAX_FILE_LINES})", file=sys.stderr)
        return 1
    allowed = f" (allowed: {', '.join(sorted(ALLOWED))})" if ALLOWED else ""
    print(f"check_sizes.py: every function in src/ within {MAX_FUNCTION_LINES} lines, every file within "
          f"{MAX_FILE_LINES}{allowed}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
