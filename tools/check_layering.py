#!/usr/bin/python3
"""The layering of docs/layout.md, checked on the includes of lib/.

Two tables of the document are the test's data. Its modules, top to bottom: a file of one
module may include a header of its own module or of one below it, never of one above. What a
module offers the modules above: another module's private header (lib/src/<module>/*.hpp) only
when that module's row lists it (a name or a pattern, `*.hpp` for the whole module, relative to
its folder). The top of lib/src/ is no module: anyone may include it. A public header
(lib/include/terratin/...) includes only public headers. Every include that breaks a rule is
printed with its file and line, and the test fails; so does a row that names no header there.

    tools/check_layering.py REPOSITORY_ROOT

The suite runs it as source.layering_follows_docs_layout (tests/CMakeLists.txt).
"""

import fnmatch
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
# A table row: | Module | `lib/src/<folder>/`... |
ROW = re.compile(r"^\| (\w+) \| `lib/src/(\w+)/`")
# The section of the offers' table, and one of its rows: | module | `header`, `header` |
OFFERS = "## What a module offers the modules above"
OFFER_ROW = re.compile(r"^\| (\w+) \| (.*)\|\s*$")


def module_order(layout):
    """The library's modules, top to bottom, as docs/layout.md lists them."""
    modules = [m.group(2) for m in map(ROW.match, layout.splitlines()) if m]
    if len(modules) < 5:
        raise SystemExit("docs/layout.md: no table of modules found")
    return modules


def offered_headers(layout, modules, root):
    """{module: [patterns of its private headers other modules may include]}, from the table
    of docs/layout.md's section OFFERS. Raises SystemExit for a row that names no module of
    the order or a pattern that matches no header of the module's folder."""
    lines = layout.splitlines()
    if OFFERS not in lines:
        raise SystemExit(f"docs/layout.md: no section '{OFFERS}'")
    offers = {}
    for line in lines[lines.index(OFFERS) + 1:]:
        if line.startswith("## "):
            break
        match = OFFER_ROW.match(line)
        if not match or match.group(1) == "Module":
            continue
        module = match.group(1)
        if module not in modules:
            raise SystemExit(f"docs/layout.md: '{module}' offers headers but is no module")
        patterns = re.findall(r"`([^`]+)`", match.group(2))
        folder = root / "lib" / "src" / module
        for pattern in patterns:
            if not any(fnmatch.fnmatch(p.relative_to(folder).as_posix(), pattern)
                       for p in folder.rglob("*.hpp")):
                raise SystemExit(f"docs/layout.md: {module} offers {pattern}, "
                                 f"which is no header of lib/src/{module}/")
        offers.setdefault(module, []).extend(patterns)
    return offers


def is_offered(target, module, offers, root):
    """Whether the private header `target` of `module` is one it offers the modules above."""
    name = target.relative_to(root / "lib" / "src" / module).as_posix()
    return any(fnmatch.fnmatch(name, pattern) for pattern in offers.get(module, []))


def module_of(path, root, modules):
    """(module, public, private-header) of a file of lib/, or (None, ...) for the top level."""
    relative = path.relative_to(root / "lib")
    parts = relative.parts
    public = parts[0] == "include"
    inner = parts[2:] if public else parts[1:]
    module = inner[0] if len(inner) > 1 and inner[0] in modules else None
    return module, public, not public and path.suffix == ".hpp"


def resolve(include, including, root):
    """The file an include names: beside the including file, else under lib/include."""
    for base in (including.parent, root / "lib" / "include", root / "lib" / "src"):
        candidate = (base / include).resolve()
        if candidate.is_file():
            return candidate
    return None


def violations(root):
    layout = (root / "docs" / "layout.md").read_text()
    modules = module_order(layout)
    offers = offered_headers(layout, modules, root)
    rank = {module: i for i, module in enumerate(modules)}
    found = []
    for path in sorted((root / "lib").rglob("*.[ch]pp")):
        source_module, source_public, _ = module_of(path, root, modules)
        for number, line in enumerate(path.read_text().splitlines(), 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = resolve(match.group(1), path, root)
            if target is None or not target.is_relative_to(root / "lib"):
                continue
            module, public, private_header = module_of(target, root, modules)
            where = f"{path.relative_to(root)}:{number}: {match.group(1)}"
            if source_public and not public:
                found.append(f"{where}: a public header includes a private one")
            if source_module is None or module is None or module == source_module:
                continue
            if rank[module] < rank[source_module]:
                found.append(f"{where}: {source_module} includes {module}, a module above it")
            elif private_header and not is_offered(target, module, offers, root):
                found.append(f"{where}: {source_module} includes a private header that {module} "
                             "does not offer")
    return found


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    found = violations(root)
    for line in found:
        print(line)
    print(f"{len(found)} include(s) against docs/layout.md's layering")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
