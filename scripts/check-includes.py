#!/usr/bin/env python3
"""Checks the include graph: each target includes only headers of the targets it links.

Usage: scripts/check-includes.py MODULE_MAP.json [--not-linking TARGETS=FORBIDDEN]...

--not-linking A,B=X,Y also checks that none of the targets A, B links any of X, Y, directly or
through any chain of links (PUBLIC or PRIVATE: a static library's private links are linked too).
A violation reads "TARGET links FORBIDDEN (TARGET -> ... -> FORBIDDEN), which it must not".
The project uses it to prove that the layers that only read results link no physics engine.

The module map is written by CMake at configure time (cmake/VisgrabModuleMap.cmake): every
target of the source tree with its folder, sources, include folders and link items. A header
belongs to the target whose folder holds it (the deepest such folder). A target may include its
own headers, those of the targets it links directly (PUBLIC or PRIVATE), and those of the targets
these pass on through PUBLIC links, transitively. Every `#include "..."` of every file in a
target's folder (sources and headers, not those of deeper targets' folders) is checked; an
include that resolves to no project header (a system or generated header) is not checked.

Prints one line per violation, "file:line: includes X of target T, which MODULE does not link",
and exits 1 if there is any (0 otherwise, 2 for a bad map). Python 3 standard library only.
"""

import json
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".cc", ".cxx", ".hh", ".inl")
LINK_ONLY = re.compile(r"^\$<LINK_ONLY:([^>]+)>$")


def real_dirs(entries, source_dir):
    """Plain absolute folders inside the source tree (generator expressions unwrapped)."""
    out = []
    for entry in entries:
        match = re.match(r"^\$<BUILD_INTERFACE:(.*)>$", entry)
        if match:
            entry = match.group(1)
        if "$<" in entry or not os.path.isabs(entry):
            continue
        entry = os.path.normpath(entry)
        if is_below(entry, source_dir):
            out.append(entry)
    return out


def is_below(path, folder):
    return path == folder or path.startswith(folder.rstrip(os.sep) + os.sep)


class Target:
    def __init__(self, entry, source_dir):
        self.name = entry["name"]
        self.folder = os.path.normpath(entry["source_dir"])
        self.sources = set()
        for s in entry.get("SOURCES", []):
            if "$<" in s:
                continue
            path = s if os.path.isabs(s) else os.path.join(self.folder, s)
            self.sources.add(os.path.normpath(path))
        self.include_dirs = real_dirs(
            entry.get("INCLUDE_DIRECTORIES", []) + entry.get("INTERFACE_INCLUDE_DIRECTORIES", []),
            source_dir,
        )
        interface = entry.get("INTERFACE_LINK_LIBRARIES", [])
        self.public = [i for i in interface if "$<" not in i]
        private = [LINK_ONLY.match(i).group(1) for i in interface if LINK_ONLY.match(i)]
        direct = entry.get("LINK_LIBRARIES", [])
        if entry["type"] == "INTERFACE_LIBRARY":
            direct = self.public
        self.direct = [i for i in direct if "$<" not in i] + private


def load(map_path):
    with open(map_path, encoding="utf-8") as f:
        data = json.load(f)
    source_dir = os.path.normpath(data["source_dir"])
    targets = {}
    for entry in data["targets"]:
        t = Target(entry, source_dir)
        targets[t.name] = t
    return source_dir, targets


def allowed_targets(target, targets):
    """The target itself, its direct links, and what those pass on through PUBLIC links."""
    allowed = {target.name}
    todo = [d for d in target.direct if d in targets]
    while todo:
        name = todo.pop()
        if name in allowed:
            continue
        allowed.add(name)
        todo.extend(d for d in targets[name].public if d in targets)
    return allowed


def folder_owners(targets):
    """folder -> targets defined there (several targets may share a folder)."""
    owners = {}
    for t in targets.values():
        owners.setdefault(t.folder, []).append(t)
    return owners


def owning_folder(path, owners):
    """The deepest target folder that holds `path`, or None."""
    folder = os.path.dirname(path)
    while True:
        if folder in owners:
            return folder
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent


def files_of(folder, owners):
    """Source and header files under `folder`, not under a deeper target folder."""
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if os.path.join(root, d) not in owners)
        for name in sorted(files):
            if name.endswith(SOURCE_SUFFIXES):
                yield os.path.join(root, name)


def header_owner(path, owners):
    """(folder, target) owning a header: the target listing it, else the one with a source of
    the same name (x.hpp goes with x.cpp), else the first defined in its folder (a header-only
    helper shared by the targets of one folder, such as a test helper, is then folder-local)."""
    folder = owning_folder(path, owners)
    if folder is None:
        return None, None
    for t in owners[folder]:
        if path in t.sources:
            return folder, t
    stem = os.path.splitext(path)[0]
    for t in owners[folder]:
        if any(os.path.splitext(s)[0] == stem for s in t.sources):
            return folder, t
    if len(owners[folder]) > 1:
        return folder, None
    return folder, owners[folder][0]


def resolve(include, including_file, roots):
    for root in [os.path.dirname(including_file)] + roots:
        candidate = os.path.normpath(os.path.join(root, include))
        if os.path.isfile(candidate):
            return candidate
    return None


def check(map_path, out=sys.stdout):
    source_dir, targets = load(map_path)
    owners = folder_owners(targets)
    roots = sorted({d for t in targets.values() for d in t.include_dirs})
    allowed = {name: allowed_targets(t, targets) for name, t in targets.items()}
    violations = 0
    checked = 0
    for folder in sorted(owners):
        group = owners[folder]
        for path in files_of(folder, owners):
            # A source listed by a target is checked for that target; any other file of the
            # folder (headers) must be includable by at least one target defined there.
            users = [t for t in group if path in t.sources] or group
            with open(path, encoding="utf-8", errors="replace") as f:
                lines = f.readlines()
            for number, line in enumerate(lines, start=1):
                match = INCLUDE.match(line)
                if not match:
                    continue
                header = resolve(match.group(1), path, roots)
                if header is None:
                    continue
                header_folder, owner = header_owner(header, owners)
                if header_folder is None or header_folder == folder:
                    continue  # not a project header, or one of this folder's own
                checked += 1
                if owner is None:
                    owner = owners[header_folder][0]
                if any(owner.name in allowed[u.name] for u in users):
                    continue
                where = os.path.relpath(path, source_dir)
                module = " or ".join(u.name for u in users)
                out.write(
                    f"{where}:{number}: includes {match.group(1)} of target {owner.name}, "
                    f"which {module} does not link\n"
                )
                violations += 1
    return violations, checked


def link_path(start, forbidden, targets):
    """The shortest chain of links from target `start` to a target or link item in `forbidden`
    (breadth first over every direct link), or None."""
    previous = {start: None}
    queue = [start]
    while queue:
        name = queue.pop(0)
        links = targets[name].direct if name in targets else []
        for d in links:
            if d in previous:
                continue
            previous[d] = name
            if d in forbidden:
                chain = [d]
                while previous[chain[-1]] is not None:
                    chain.append(previous[chain[-1]])
                return list(reversed(chain))
            queue.append(d)
    return None


def check_not_linking(map_path, rules, out=sys.stdout):
    """rules: [(targets, forbidden)]; returns the number of violations."""
    _, targets = load(map_path)
    violations = 0
    for names, forbidden in rules:
        for name in names:
            if name not in targets:
                raise KeyError(f"--not-linking names target {name}, which the map lacks")
            chain = link_path(name, set(forbidden), targets)
            if chain:
                out.write(f"{name} links {chain[-1]} ({' -> '.join(chain)}), which it must not\n")
                violations += 1
    return violations


def parse_rules(args):
    rules = []
    if len(args) % 2 != 0:
        raise ValueError("--not-linking needs TARGETS=FORBIDDEN")
    for flag, value in zip(args[::2], args[1::2]):
        if flag != "--not-linking" or value.count("=") != 1:
            raise ValueError(f"expected --not-linking A,B=X,Y, got {flag} {value}")
        left, right = value.split("=")
        rules.append(([n for n in left.split(",") if n], [n for n in right.split(",") if n]))
    return rules


def main(argv):
    if len(argv) < 2:
        sys.stderr.write(__doc__)
        return 2
    try:
        rules = parse_rules(argv[2:])
    except ValueError as e:
        sys.stderr.write(f"check-includes: {e}\n")
        return 2
    try:
        violations, checked = check(argv[1])
        link_violations = check_not_linking(argv[1], rules)
    except (OSError, KeyError, ValueError) as e:
        sys.stderr.write(f"check-includes: cannot read the module map {argv[1]}: {e}\n")
        return 2
    if link_violations:
        print(f"check-includes: {link_violations} targets link what they must not")
        return 1
    if rules:
        names = sorted({n for left, _ in rules for n in left})
        print(f"check-includes: {', '.join(names)} link none of the targets they must not")
    if violations:
        print(f"check-includes: {violations} of {checked} includes of other targets' headers "
              "are of targets not linked")
        return 1
    print(f"check-includes: all {checked} includes of other targets' headers are of linked targets")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
