#!/usr/bin/python3
"""The layering of docs/layout.md, checked on the includes of lib/.

The document's table of modules, top to bottom, is the test's data: a file of one module may
include a header of its own module or of one below it, never of one above; another module's
private header (lib/src/<module>/*.hpp) only from lib/src/mesh/, lib/src/parallel/ or the top
of lib/src/; a public header (lib/include/terratin/...) only public headers. Every include that
breaks a rule is printed with its file and line, and the test fails.

    tools/check_layering.py REPOSITORY_ROOT

Not yet in the suite: it becomes a test once the includes it lists are gone.
"""

import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
# A table row: | Module | `lib/src/<folder>/`... |
ROW = re.compile(r"^\| (\w+) \| `lib/src/(\w+)/`")


def module_order(layout):
    """The library's modules, top to bottom, as docs/layout.md lists them."""
    modules = [m.group(2) for m in map(ROW.match, layout.splitlines()) if m]
    if len(modules) < 5:
        raise SystemExit("docs/layout.md: no table of modules found")
    return modules


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
    modules = module_order((root / "docs" / "layout.md").read_text())
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
            elif private_header and module not in ("mesh", "parallel"):
                found.append(f"{where}: {source_module} includes a private header of {module}")
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
