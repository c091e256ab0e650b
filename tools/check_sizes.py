#!/usr/bin/python3
"""The size limits of docs/style: no file of lib/ or tools/ over 500 lines, no function over 60.

A function is a brace block opened at namespace or class scope after a parameter list; its
length runs from the line of its name to its closing brace. A function that is mostly
one data table (a brace opened after `=`, `,` or `(`, over half its lines) is a table, not
over the limit. Comments, strings and character literals are blanked before braces are
counted, so a brace in a message does not open a block.

    tools/check_sizes.py REPOSITORY_ROOT

Prints every file and function over its limit and exits 1 if there is one. The suite runs it as
source.files_and_functions_within_their_sizes (tests/CMakeLists.txt).
"""

import pathlib
import re
import sys

FILE_LIMIT = 500
FUNCTION_LIMIT = 60
FOLDERS = ("lib", "tools")
CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else|try)\b\s*(\(|$)")
SCOPE = re.compile(r"\b(namespace|class|struct|union|enum)\b")


def blank_comments_and_literals(text):
    """The text with comments and literals replaced by spaces, newlines kept."""
    pattern = re.compile(
        r'//[^\n]*|/\*.*?\*/|R"(?P<d>[^(]*)\(.*?\)(?P=d)"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'',
        re.S)
    text = pattern.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)
    directive = re.compile(r"^[ \t]*#(?:[^\n]*\\\n)*[^\n]*", re.M)
    return directive.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def long_functions(text):
    """(first line, lines) of each function of the text longer than the limit."""
    text = blank_comments_and_literals(text)
    found = []
    stack = []  # each open brace: [kind, first line, lines of its longest data table]
    head_start = 0  # offset where the text before the next brace begins
    line_of = lambda offset: text.count("\n", 0, offset) + 1
    for index, char in enumerate(text):
        if char == ";":
            head_start = index + 1
        elif char == "{":
            head = text[head_start:index]
            kind = classify(head, stack)
            first = head_start + len(head) - len(head.lstrip())
            stack.append([kind, line_of(first), 0])
            head_start = index + 1
        elif char == "}":
            if stack:
                kind, first, table_lines = stack.pop()
                length = line_of(index) - first + 1
                if kind == "table" and stack and stack[-1][0] != "table":
                    for entry in reversed(stack):
                        if entry[0] == "function":
                            entry[2] = max(entry[2], length)
                            break
                if kind == "function" and length > FUNCTION_LIMIT and table_lines < length / 2:
                    found.append((first, length))
            head_start = index + 1
    return found


def classify(head, stack):
    """What a brace opens: a namespace or class scope, a function, a data table or a block."""
    head = " ".join(head.split())
    if re.search(r"[=,(\[{]\s*$", head) or head == "":
        # An initializer: a table when it stands in a function (its lines are data).
        return "table" if any(kind == "function" for kind, *_ in stack) else "block"
    if any(kind in ("function", "block", "table") for kind, *_ in stack):
        return "block"
    declaration = re.sub(r"^template\s*<.*?>\s*", "", head)
    if SCOPE.match(declaration) or head.startswith("extern"):
        return "scope"
    if "(" in head and not CONTROL.match(head):
        return "function"
    return "block"


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    problems = []
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*.[ch]pp")):
            text = path.read_text()
            where = path.relative_to(root)
            lines = text.count("\n")
            if lines > FILE_LIMIT:
                problems.append(f"{where}: {lines} lines (limit {FILE_LIMIT})")
            for first, length in long_functions(text):
                problems.append(f"{where}:{first}: function of {length} lines (limit {FUNCTION_LIMIT})")
    for problem in problems:
        print(problem)
    if problems:
        print(f"{len(problems)} over the size limits")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
