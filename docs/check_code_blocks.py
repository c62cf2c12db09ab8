#!/usr/bin/python3
"""Runs every code block the documentation shows, so the docs cannot drift (issue 30).

    docs/check_code_blocks.py [--build BUILD] [--list] [PAGE.md ...]

Default pages: README.md and every docs/**/*.md. Each page runs in a fresh work directory,
BUILD/docs-run/<page>/, which links configs/, data/, examples/, python/, tools/, scripts/,
tests/, bench/ and build/ from the source tree, with BUILD and tools/ first on PATH (so
`tcpmsim` and `tcpmsim-plot` are the ones just built; `python3` is /usr/bin/python3) and
BUILD/python on PYTHONPATH. The blocks of a page run
in their order:

- ``bash``/``sh``: each block in its own `bash -euo pipefail`.
- ``python``: in one interpreter per page, so a later block sees an earlier block's names.
- a block whose first line is ``# file: NAME`` is written to NAME in the work directory (a file
  a tutorial asks the reader to create); later blocks use it. In any language.
- a block whose first line is ``# PATH`` or ``# from: PATH`` (then ``: comment`` or
  `` (comment)`` may follow), PATH a file of the source tree, is an excerpt: a YAML excerpt's keys and values must be the file's (flow or block style), any
  other excerpt's lines (but ``...`` lines; comments and spacing aside) must appear in that
  file in the same order.
- ``text``, ``console``, ``none`` and ``output`` blocks show output; nothing runs them.
- any other block must follow a MyST comment ``% not run: REASON`` (or, in the README, which
  GitHub shows, ``<!-- not run: REASON -->``) on the line before it; the
  same comment before a bash or python block skips it (a command that installs, or needs a
  cluster). The reasons are listed at the end.
- ``% exit: N`` before a bash block: the block must end with exit code N (an error shown on
  purpose); ``% output`` before a text block: each of its lines must be in what the run block
  before it printed (stdout and stderr), so a message or a number shown cannot drift.

A block that fails (non-zero exit, an exception, an excerpt that is not in its file, a block
neither run nor marked) fails the script with the page, the block's line and its output."""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

SOURCE = Path(__file__).resolve().parent.parent
SHELL = {"bash", "sh", "shell"}
PYTHON = {"python", "py", "python3"}
OUTPUT = {"text", "console", "none", "output", ""}
LINKED = ["configs", "data", "examples", "python", "tools", "scripts", "tests", "bench"]
FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*(\{code-block\}\s*)?([\w+-]*)")
# A MyST comment ("% not run: ...") or, where the page is also read on GitHub (the README), an
# HTML comment ("<!-- not run: ... -->"), which neither shows.
COMMENT = r"^(?:%\s*{0}|<!--\s*{0}\s*-->)$"
NOT_RUN = re.compile(COMMENT.format(r"not run:\s*(.+?)"))
EXIT = re.compile(COMMENT.format(r"exit:\s*(\d+)\s*"))
OUTPUT_CHECK = re.compile(COMMENT.format(r"output\s*"))

# Runs the page's Python blocks in one namespace: reads a block's length and text from stdin,
# executes it, answers with a status line.
PYTHON_SERVER = r"""
import sys, traceback
namespace = {"__name__": "__main__"}
stdin = sys.stdin.buffer
while True:
    header = stdin.readline()
    if not header:
        break
    code = stdin.read(int(header)).decode()
    try:
        exec(compile(code, "<docs block>", "exec"), namespace)
        status = "ok"
    except SystemExit as stop:
        status = "ok" if not stop.code else "failed"
    except BaseException:
        traceback.print_exc()
        status = "failed"
    sys.stdout.flush(); sys.stderr.flush()
    sys.stdout.write("\n@@docs-block %s@@\n" % status)
    sys.stdout.flush()
"""


def comment_value(pattern, line):
    """What a marker comment says (the reason, the exit code), whichever form it has; None
    when `line` is not that marker."""
    match = pattern.match(line)
    return next((group for group in match.groups() if group is not None), "") if match else None


class Block:
    def __init__(self, page, line, language, text, not_run, exit_code=0, checked_output=False):
        self.page, self.line, self.language, self.text, self.not_run = (
            page, line, language, text, not_run)
        self.exit_code, self.checked_output = exit_code, checked_output

    def where(self):
        return f"{self.page.relative_to(SOURCE)}:{self.line}"


def blocks_of(page):
    lines = page.read_text().splitlines()
    index = 0
    while index < len(lines):
        match = FENCE.match(lines[index])
        if not match:
            index += 1
            continue
        indent, fence, _, language = match.groups()
        before = lines[index - 1].strip() if index > 0 else ""
        reason = comment_value(NOT_RUN, before)
        exit_code = int(comment_value(EXIT, before) or 0)
        checked_output = OUTPUT_CHECK.match(before) is not None
        body, index = [], index + 1
        while index < len(lines) and not lines[index].strip().startswith(fence):
            body.append(lines[index][len(indent):] if lines[index].startswith(indent) else lines[index])
            index += 1
        # MyST directive options (:caption: ...) are not part of the code.
        while body and re.match(r"^:\w[\w-]*:", body[0]):
            body.pop(0)
        yield Block(page, index - len(body), language.lower(), "\n".join(body) + "\n", reason,
                    exit_code, checked_output)
        index += 1


def header_path(block):
    first = block.text.splitlines()[0].strip() if block.text.strip() else ""
    match = re.match(r"^(#|//|%)\s*(file:|from:)?\s*([\w./-]+?)(:\s.*|\s+\(.*)?$", first)
    if not match:
        return None, None
    kind, path = match.group(2), match.group(3)
    if kind == "file:":
        return "file", path
    if (SOURCE / path).is_file():
        return "excerpt", path
    return None, None


def code_lines(text, comment="#"):
    """The lines of a YAML/shell text without comments and with single spaces, for excerpts:
    the docs may annotate a file's lines, never change them."""
    lines = []
    for line in text.splitlines():
        quoted = False
        for position, char in enumerate(line):
            if char in "'\"":
                quoted = not quoted
            if (line.startswith(comment, position) and not quoted
                    and (position == 0 or line[position - 1].isspace())):
                line = line[:position]
                break
        line = " ".join(line.split())
        if line and line != "...":
            lines.append(line)
    return lines


def subset_problem(shown, have, where="the file"):
    """Why the YAML the docs show is not part of the file's (None when it is). An ellipsis, as
    a value, a list or a key, stands for what the docs leave out."""
    if shown == "..." or shown == ["..."]:
        return None
    if isinstance(shown, dict) and isinstance(have, dict):
        for key, value in shown.items():
            if key == "...":
                continue
            if key not in have:
                return f"{where} has no key {key!r}"
            problem = subset_problem(value, have[key], f"{where}.{key}")
            if problem:
                return problem
        return None
    if isinstance(shown, list) and isinstance(have, list) and len(shown) == len(have):
        for index, (a, b) in enumerate(zip(shown, have)):
            problem = subset_problem(a, b, f"{where}[{index}]")
            if problem:
                return problem
        return None
    return None if shown == have else f"{where} is {have!r} in the file, {shown!r} here"


def yaml_excerpt_problem(block, path):
    """A YAML excerpt is compared as data: flow or block style, its keys and values must be the
    file's. None when the block is no YAML document of its own (then the lines are compared)."""
    import yaml
    try:
        shown = yaml.safe_load("\n".join(l for l in block.text.splitlines() if l.strip() != "..."))
    except yaml.YAMLError:
        return None
    if not isinstance(shown, dict):
        return None
    return subset_problem(shown, yaml.safe_load((SOURCE / path).read_text())) or ""


def check_excerpt(block, path):
    if path.endswith((".yaml", ".yml")):
        problem = yaml_excerpt_problem(block, path)
        if problem is not None:
            return f"{path}: {problem}" if problem else None
    comment = "//" if block.language in ("cpp", "c++", "c") else "#"
    wanted = code_lines("\n".join(block.text.splitlines()[1:]), comment)
    have = code_lines((SOURCE / path).read_text(), comment)
    position = 0
    for line in wanted:
        while position < len(have) and have[position] != line:
            position += 1
        if position == len(have):
            return f"the line {line!r} is not in {path} (in this order; comments aside)"
        position += 1
    return None


class Page:
    def __init__(self, page, build):
        self.page, self.build = page, build
        slug = str(page.relative_to(SOURCE)).replace("/", "_").removesuffix(".md")
        self.workdir = build / "docs-run" / slug
        shutil.rmtree(self.workdir, ignore_errors=True)
        self.workdir.mkdir(parents=True)
        for name in LINKED:
            (self.workdir / name).symlink_to(SOURCE / name)
        (self.workdir / "build").symlink_to(build.resolve())
        # `python3` in a block is Debian's, the one the module is built for (a machine may put
        # another interpreter first on PATH).
        shims = self.workdir / ".bin"
        shims.mkdir()
        (shims / "python3").symlink_to("/usr/bin/python3")
        self.env = dict(os.environ)
        self.env["PATH"] = f"{shims}:{build.resolve()}:{SOURCE / 'tools'}:{self.env.get('PATH', '')}"
        self.env["PYTHONPATH"] = f"{build.resolve() / 'python'}:{SOURCE / 'tools'}"
        self.env["MPLBACKEND"] = "Agg"
        self.env["TCPMSIM_PLOT_TOOL"] = str(SOURCE / "tools" / "tcpmsim-plot")
        self.python = None

    def run_shell(self, block):
        done = subprocess.run(["bash", "-euo", "pipefail", "-c", block.text], cwd=self.workdir,
                              env=self.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True, timeout=900)
        if done.returncode != block.exit_code:
            return False, f"{done.stdout}(exit code {done.returncode}, expected {block.exit_code})"
        return True, done.stdout

    def run_python(self, block):
        if self.python is None:
            self.python = subprocess.Popen(["/usr/bin/python3", "-u", "-c", PYTHON_SERVER],
                                           cwd=self.workdir, env=self.env, stdin=subprocess.PIPE,
                                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        code = block.text.encode()
        self.python.stdin.write(b"%d\n" % len(code) + code)
        self.python.stdin.flush()
        output = []
        for raw in self.python.stdout:
            line = raw.decode(errors="replace")
            status = re.match(r"^@@docs-block (\w+)@@$", line.strip())
            if status:
                return status.group(1) == "ok", "".join(output)
            output.append(line)
        return False, "".join(output) + "(the interpreter ended)"

    def close(self):
        if self.python is not None:
            self.python.stdin.close()
            self.python.wait()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pages", nargs="*", type=Path)
    parser.add_argument("--build", type=Path, default=SOURCE / "build")
    parser.add_argument("--list", action="store_true", help="list the blocks, run nothing")
    args = parser.parse_args()
    pages = [p.resolve() for p in args.pages] or (
        [SOURCE / "README.md"] + sorted((SOURCE / "docs").rglob("*.md")))
    pages = [p for p in pages if "docs-run" not in p.parts and "_build" not in p.parts]
    counts = {"run": 0, "written": 0, "excerpt": 0, "output": 0}
    not_run, failures = [], []
    for path in pages:
        blocks = list(blocks_of(path))
        if not blocks:
            continue
        page = None if args.list else Page(path, args.build)
        last_output = ""
        for block in blocks:
            kind, target = header_path(block)
            if block.not_run:
                not_run.append((block.where(), block.not_run))
                continue
            if kind == "excerpt":
                counts["excerpt"] += 1
                problem = check_excerpt(block, target)
                if problem:
                    failures.append((block, problem))
                continue
            if kind == "file":
                counts["written"] += 1
                if page:
                    (page.workdir / target).parent.mkdir(parents=True, exist_ok=True)
                    (page.workdir / target).write_text(block.text)
                continue
            if block.language in OUTPUT:
                counts["output"] += 1
                if block.checked_output and page:
                    missing = [l.strip() for l in block.text.splitlines()
                               if l.strip() and l.strip() not in last_output]
                    if missing:
                        failures.append((block, "not in the output of the block before it: "
                                                 + "; ".join(missing[:3])))
                continue
            if block.language not in SHELL | PYTHON:
                failures.append((block, f"a {block.language} block is neither run, a file, an "
                                        "excerpt, nor marked '% not run: REASON'"))
                continue
            counts["run"] += 1
            if args.list:
                print(f"{block.where()}: {block.language}")
                continue
            print(f"docs: {block.where()} ({block.language})", flush=True)
            ok, output = (page.run_shell if block.language in SHELL else page.run_python)(block)
            last_output = output
            if not ok:
                failures.append((block, output[-4000:]))
        if page:
            page.close()
    for where, reason in not_run:
        print(f"docs: not run: {where}: {reason}")
    print("docs: {run} blocks run, {written} files written, {excerpt} excerpts checked, "
          "{output} outputs shown, {n} not run (reasons above)".format(n=len(not_run), **counts))
    for block, problem in failures:
        print(f"docs: FAILED {block.where()} ({block.language}):\n{problem}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
