#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The docs check: every Markdown file's relative links resolve, every roifem / roifem-mpi command
line it quotes parses, and the --help texts quoted in docs/commands.md are the CLI's.

usage: check_docs.py SOURCE_DIR ROIFEM ROIFEM_MPI

Command lines come from fenced code blocks marked sh, bash or console and from code spans with a
command and at least one argument (`roifem run` alone names a command; `roifem run X --out Y` is a
command line). Each is run from SOURCE_DIR as `PROGRAM --check-args ARGS`: CLI11 parses it and
checks its options, their values and its input files, and nothing runs. `mpirun [options]
roifem-mpi ...` and `scripts/mpirun.sh ...` check the roifem-mpi part (PETSc's options after `--`
are PETSc's own). Placeholders stand for shipped files (PLACEHOLDERS); `[...]` marks an optional
part and is left out. A block whose previous line is `<!-- example: not run -->` is not run.
`<!-- help: COMMAND -->` (or `<!-- help-mpi: COMMAND -->`) above a block quotes `roifem COMMAND
--help` (or roifem-mpi's), which must be the CLI's, character for character.
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile

PLACEHOLDERS = {
    "SCENARIO.toml": "scenarios/paper-setup1.toml", "SCENARIO": "scenarios/paper-setup1.toml",
    "MESH": "meshes/brain-800.msh", "MESH.msh": "meshes/brain-800.msh",
    "N": "800", "E": "0.5", "COMMAND": "run",
}
SCRATCH = {"DIR", "OUT", "CACHE", "FILE.msh", "F", "OUT.png"}  # written by the command: a scratch path each
PROGRAMS = {"roifem": "roifem", "roifem-mpi": "roifem-mpi",
            "build/release/src/app/roifem": "roifem", "build/release/src/app/roifem-mpi": "roifem-mpi"}
SKIP_DIRS = {".git", "build", "fuzz", "results", "bench-meshes", "node_modules"}


def markdown_files(root):
    for directory, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith(".")]
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(directory, name)


def links(path, text):
    """(target, line) of each relative link or image."""
    for match in re.finditer(r"!?\[[^\]]*\]\(([^)\s]+)\)", text):
        target = match.group(1)
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        yield target.split("#")[0], text.count("\n", 0, match.start()) + 1


def blocks(text):
    """(info, first line number, lines, marker) of each fenced block; marker: the comment above it."""
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        fence = re.match(r"^\s*```(\S*)", lines[i])
        if not fence:
            i += 1
            continue
        marker = ""
        j = i - 1
        while j >= 0 and not lines[j].strip():
            j -= 1
        if j >= 0 and lines[j].strip().startswith("<!--"):
            marker = lines[j].strip()
        body = []
        k = i + 1
        while k < len(lines) and not re.match(r"^\s*```", lines[k]):
            body.append(lines[k])
            k += 1
        yield fence.group(1), i + 2, body, marker
        i = k + 1


def command_lines(body):
    """Logical lines of a shell block: continuations joined, prompts dropped."""
    joined, current = [], ""
    for line in body:
        line = re.sub(r"^\s*\$\s+", "", line)
        if line.rstrip().endswith("\\"):
            current += line.rstrip()[:-1] + " "
            continue
        joined.append(current + line)
        current = ""
    return joined


def command_of(tokens):
    """(program, arguments) of a command line, or None."""
    while tokens and re.match(r"^[A-Z_][A-Z0-9_]*=", tokens[0]):  # VAR=value prefixes
        tokens = tokens[1:]
    if not tokens:
        return None
    if tokens[0] in ("mpirun", "mpiexec", "scripts/mpirun.sh"):
        for i, t in enumerate(tokens):
            if t in PROGRAMS and PROGRAMS[t] == "roifem-mpi":
                return "roifem-mpi", tokens[i + 1:]
        return None
    if tokens[0] in PROGRAMS:
        return PROGRAMS[tokens[0]], tokens[1:]
    return None


class Checker:
    def __init__(self, root, binaries):
        self.root, self.binaries = root, binaries
        self.failures, self.parsed, self.examples, self.helps, self.link_count = [], 0, 0, 0, 0
        self.scratch = tempfile.mkdtemp(prefix="roifem-docs-")

    def fail(self, where, what):
        self.failures.append(f"{where}: {what}")

    def arguments(self, args, where):
        """The arguments with placeholders filled in; None (and a failure) for an unknown one."""
        out = []
        optional = False
        for a in args:
            if a == "--":
                break  # PETSc's options
            if a.startswith("["):  # an optional part, to its closing bracket, is left out
                optional = not a.endswith("]")
                continue
            if optional:
                optional = not a.endswith("]")
                continue
            if a in PLACEHOLDERS:
                out.append(PLACEHOLDERS[a])
            elif a in SCRATCH:
                self.parsed_scratch = getattr(self, "parsed_scratch", 0) + 1
                out.append(os.path.join(self.scratch, f"out{self.parsed_scratch}" + (".msh" if "msh" in a or a == "F" else "")))
            elif re.fullmatch(r"[A-Z][A-Z0-9_]*(\.[a-z0-9.\[\]]+)?", a) and not re.fullmatch(r"[0-9.]+", a):
                self.fail(where, f"placeholder '{a}' stands for nothing the check knows: use one of "
                                 f"{sorted(PLACEHOLDERS) + sorted(SCRATCH)}, or mark the block <!-- example: not run -->")
                return None
            else:
                out.append(a)
        return out

    def check_command(self, line, where):
        try:
            tokens = shlex.split(line, comments=True)
        except ValueError as e:
            self.fail(where, f"cannot split '{line}': {e}")
            return
        found = command_of(tokens)
        if not found:
            return
        program, args = found
        if self.binaries[program] == "-":  # built without PETSc: roifem-mpi's lines cannot be checked
            return
        args = self.arguments(args, where)
        if args is None:
            return
        run = subprocess.run([self.binaries[program], "--check-args", *args], cwd=self.root, capture_output=True, text=True)
        self.parsed += 1
        if run.returncode != 0:
            self.fail(where, f"'{line.strip()}' does not parse: {(run.stderr or run.stdout).strip()}")

    def check_file(self, path):
        text = open(path, encoding="utf-8").read()
        name = os.path.relpath(path, self.root)
        for target, line in links(path, text):
            self.link_count += 1
            if not os.path.exists(os.path.join(os.path.dirname(path), target)):
                self.fail(f"{name}:{line}", f"link to '{target}', which does not exist")
        code_lines = set()
        for info, first, body, marker in blocks(text):
            code_lines.update(range(first - 2, first + len(body)))  # 0-based: the fences and the body
            help_marker = re.match(r"<!--\s*help(-mpi)?:\s*([a-z-]*)\s*-->", marker)
            if help_marker:
                self.check_help(name, first, body, "roifem-mpi" if help_marker.group(1) else "roifem", help_marker.group(2))
                continue
            if info not in ("sh", "bash", "console", "shell"):
                continue
            if "example: not run" in marker:
                self.examples += 1
                continue
            for offset, line in enumerate(command_lines(body)):
                self.check_command(line, f"{name}:{first + offset}")
        # Code spans outside blocks: a command with at least one argument.
        lines = text.split("\n")
        prose = "\n".join("" if i in code_lines else l for i, l in enumerate(lines))
        for match in re.finditer(r"`([^`]+)`", prose):
            span = " ".join(match.group(1).split())
            tokens = span.split()
            found = command_of(tokens)
            if found and len(found[1]) >= 2:
                self.check_command(span, f"{name}:{prose.count(chr(10), 0, match.start()) + 1}")

    def check_help(self, name, first, body, program, command):
        args = [command, "--help"] if command else ["--help"]
        run = subprocess.run([self.binaries[program], *args], cwd=self.root, capture_output=True, text=True)
        self.helps += 1
        quoted = "\n".join(l.rstrip() for l in body).strip("\n")
        actual = "\n".join(l.rstrip() for l in run.stdout.split("\n")).strip("\n")
        if os.path.abspath(self.root) in actual:
            self.fail(f"{name}:{first}", f"`{program} {' '.join(args)}` prints this checkout's path "
                                         f"({self.root}), which no other checkout shares")
        elif run.returncode != 0 or quoted != actual:
            self.fail(f"{name}:{first}", f"the quoted `{program} {' '.join(args)}` is not the CLI's; "
                                         f"regenerate it with scripts/docs-help.sh")


def main(root, roifem, roifem_mpi):
    checker = Checker(root, {"roifem": roifem, "roifem-mpi": roifem_mpi})
    files = list(markdown_files(root))
    for path in files:
        checker.check_file(path)
    print(f"docs: {len(files)} Markdown files, {checker.link_count} relative links, {checker.parsed} command lines parsed, "
          f"{checker.examples} examples not run, {checker.helps} --help texts")
    for f in checker.failures:
        print("FAIL", f)
    if checker.failures:
        sys.exit(1)
    print("docs: ok")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
