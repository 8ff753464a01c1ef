#!/usr/bin/env python3
"""Files and functions too long to read in one sitting (the house rules, docs/architecture.md).

    scripts/check_sizes.py [--file-lines 500] [--function-lines 100] [ROOT]

Lists every hand-written C++ source file under ROOT (default: the repository)
longer than --file-lines, and every function body longer than --function-lines,
leaving out tests/ (test files are lists of cases), build folders and generated
code. Exits 1 if anything is listed, 0 otherwise. Standard library only.

A function is found as a brace block opened at namespace or class scope after a
closing parenthesis (a definition, not a control statement or an initialiser);
its length runs from the line of its signature's name to its closing brace. The
scan strips comments, strings and character literals first, so braces inside
them do not count.
"""
import argparse
import os
import re
import sys

SKIPPED_DIRS = {"build", "tests", ".git", "generated", "node_modules"}
SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".cc")
CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else)\s*(\(|$)")


def strip_code(text):
    """The text with comments, strings and character literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
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
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + (m.group(1) if m else "") + '"', i)
            j = n if end < 0 else end + len(m.group(1) if m else "") + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j + 1]))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def long_functions(text, limit):
    code = strip_code(text)
    scopes = []  # per open brace: "ns" (namespace, class, extern), "fn" or "other"
    head_start = 0  # where the text before the next brace starts (after ; { or })
    found = []
    for pos, c in enumerate(code):
        if c == "{":
            head = code[head_start:pos]
            enclosing_is_scope = all(s[0] == "ns" for s in scopes)
            if re.search(r"\b(namespace|class|struct|union|enum)\b[^()]*$", head) or 'extern' in head and '"' in text[head_start:pos]:
                kind = "ns"
            elif enclosing_is_scope and ")" in head and not CONTROL.search(head.strip().split("\n")[-1]) \
                    and not re.search(r"=\s*$", head.strip()):
                kind = "fn"
                name = re.search(r"([~\w:]+(?:operator\S*)?)\s*\(", head)
                start_line = code.count("\n", 0, head_start + (name.start() if name else 0)) + 1
                scopes.append(("fn", start_line, name.group(1) if name else "?"))
                head_start = pos + 1
                continue
            else:
                kind = "other"
            scopes.append((kind, 0, ""))
            head_start = pos + 1
        elif c == "}":
            if scopes:
                kind, start_line, name = scopes.pop()
                if kind == "fn":
                    end_line = code.count("\n", 0, pos) + 1
                    if end_line - start_line + 1 > limit:
                        found.append((start_line, end_line - start_line + 1, name))
            head_start = pos + 1
        elif c == ";":
            head_start = pos + 1
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("root", nargs="?", default=os.path.join(os.path.dirname(__file__), ".."))
    parser.add_argument("--file-lines", type=int, default=500)
    parser.add_argument("--function-lines", type=int, default=100)
    args = parser.parse_args()
    root = os.path.normpath(args.root)
    problems = 0
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("build"))
        for name in sorted(files):
            if not name.endswith(SOURCE_SUFFIXES):
                continue
            path = os.path.join(folder, name)
            rel = os.path.relpath(path, root)
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            lines = text.count("\n")
            if lines > args.file_lines:
                print(f"{rel}: {lines} lines (limit {args.file_lines})")
                problems += 1
            for start, length, fn in long_functions(text, args.function_lines):
                print(f"{rel}:{start}: {fn}: {length} lines (limit {args.function_lines})")
                problems += 1
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
