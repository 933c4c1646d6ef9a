#!/usr/bin/python3
"""Runs the code blocks of README.md and docs/*.md as written.

Every fenced block is either code that runs or declared text:
  sh, bash   run with bash (set -eo pipefail) in a scratch folder per
             document (its blocks run in order and share files), with
             BUILD/bin first on PATH, HOME in the scratch folder and a
             private LCM URL (LCM_DEFAULT_URL; every udpm://239.255.76.67:7667
             URL in a block is replaced by it: its own port, ttl=0);
  lua        run with lua5.2, after generating the message types with
             lcm-gen --lua into ~/.cache/mrsim/lua_types and setting
             LUA_PATH, as docs/gait.md tells;
  cpp        a fragment: its #include lines, then the rest inside main(),
             built against the development install of BUILD (CMake,
             find_package(mrsim)) and run;
  python     run with /usr/bin/python3, PYTHONPATH=BUILD/python (not run,
             and said so, until that package is built);
  text, xml, output, ...   not code (counted, never run).
A block without a language is an error: say which it is.

An HTML comment right before a block tunes it (invisible when rendered):
  <!-- docs-runner: WORD ... -->   on one line, or with lines after the
                                   first: a setup script (sh) or code put
                                   before the block (lua, cpp: a prelude)
  slow            run only with --slow (the slower ctest label)
  root            needs root: run only with --slow, as root, when
                  MRSIM_DOCS_ROOT=1; otherwise reported as not run
  display         run under xvfb-run (a virtual X display)
  manual REASON   never run (interactive, or runs this very suite); the
                  reason is printed in every report
  stop=PROG@S,... SIGINT every process named PROG of the block once it has
                  run S seconds (a program that runs until Ctrl-C); it must
                  then end as Ctrl-C ends it (status 0 or 130).
                  CMD:PROC@S: the command typed is CMD, its process PROC
                  (a script that runs java)
  timeout=S       the block's limit (default 180 s, 1200 with slow)
  exit=N          the exit status the block is meant to end with
Processes a block left in the background are stopped (SIGINT, then
SIGKILL) when it ends. Exit status: 0 when every block run passed, 1
otherwise, 2 for a usage or parse error.
"""

import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

RUN_LANGS = {"sh", "bash", "lua", "cpp", "python"}
TEXT_LANGS = {"text", "xml", "output", "console", "ini", "csv", "json"}
DIRECTIVE = re.compile(r"<!--\s*docs-runner:(.*?)-->", re.S)
FENCE = re.compile(r"^```([A-Za-z0-9_+-]*)[^\n]*\n(.*?)^```[ \t]*$", re.M | re.S)
DEFAULT_URL = re.compile(r"udpm://239\.255\.76\.67:7667(\?ttl=\d+)?")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# What the docs refer to relative to the repository root.
LINKED = ["scenarios", "launch", "examples", "scripts", "lcmtypes", "gaits",
          "lua_controller"]


class Block:
    def __init__(self, path, line, lang, code, words, prelude):
        self.path, self.line, self.lang, self.code = path, line, lang, code
        self.words, self.prelude = words, prelude
        self.slow = "slow" in words
        self.root = "root" in words
        self.display = "display" in words
        self.manual = words.get("manual")
        self.stops = []
        for item in filter(None, words.get("stop", "").split(",")):
            name, _, seconds = item.partition("@")
            command, _, process = name.partition(":")
            self.stops.append((command, (process or command)[:15],
                               float(seconds or 5)))
        self.timeout = float(words.get("timeout", 0)) or None
        self.exit = int(words.get("exit", 0))

    def where(self):
        return "%s:%d" % (os.path.relpath(self.path, ROOT), self.line)


def parse_words(text):
    words = {}
    tokens = text.split()
    i = 0
    while i < len(tokens):
        token = tokens[i]
        if token == "manual":
            words["manual"] = " ".join(tokens[i + 1:]) or "no reason given"
            break
        key, eq, value = token.partition("=")
        words[key] = value if eq else True
        i += 1
    return words


def parse(path):
    text = open(path, encoding="utf-8").read()
    blocks, errors = [], []
    for m in FENCE.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        lang = m.group(1).lower()
        before = text[:m.start()].rstrip()
        words, prelude = {}, ""
        if before.endswith("-->"):
            start = before.rfind("<!--")
            d = DIRECTIVE.fullmatch(before[start:])
            if d:
                first, _, rest = d.group(1).partition("\n")
                words, prelude = parse_words(first), rest
        if not lang:
            errors.append("%s:%d: a block without a language (sh to run it, "
                          "text for output or syntax)" %
                          (os.path.relpath(path, ROOT), line))
            continue
        blocks.append(Block(path, line, lang, m.group(2), words, prelude))
    return blocks, errors


class Runner:
    def __init__(self, args):
        self.args = args
        self.build = os.path.abspath(args.build)
        self.scratch_root = os.path.abspath(args.scratch or os.path.join(
            self.build, "docs_runner" + ("_slow" if args.slow else "")))
        offset = int(os.environ.get("MRSIM_TEST_PORT_OFFSET", "0") or 0)
        self.url = "udpm://239.255.76.67:%d?ttl=0" % (args.port + offset)
        self.cpp_prefix = None
        self.results = []  # (block, verdict, seconds, detail)

    def env(self, scratch):
        env = dict(os.environ)
        # `python3` in a block is the interpreter the package was built for
        # (Debian's, with numpy), whatever comes first on the caller's PATH.
        pybin = os.path.join(scratch, ".python-bin")
        os.makedirs(pybin, exist_ok=True)
        link = os.path.join(pybin, "python3")
        if not os.path.lexists(link):
            os.symlink("/usr/bin/python3", link)
        env["PATH"] = os.pathsep.join(
            [os.path.join(self.build, "bin"), pybin, env["PATH"]])
        env["HOME"] = scratch
        env["LCM_DEFAULT_URL"] = self.url
        env["MRSIM_DOCS_BUILD"] = self.build
        env.pop("DISPLAY", None)
        env.pop("WAYLAND_DISPLAY", None)
        return env

    def scratch_for(self, path):
        name = os.path.relpath(path, ROOT).replace("/", "_")
        scratch = os.path.join(self.scratch_root, name)
        shutil.rmtree(scratch, ignore_errors=True)
        os.makedirs(scratch)
        for entry in LINKED:
            if os.path.exists(os.path.join(ROOT, entry)):
                os.symlink(os.path.join(ROOT, entry), os.path.join(scratch, entry))
        os.symlink(self.build, os.path.join(scratch, "build"))
        return scratch

    def run_process(self, argv, block, scratch, env):
        """Runs argv in its own session; returns (status, output)."""
        limit = block.timeout or (1200 if block.slow else 180)
        if block.display:
            argv = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24"] + argv
        log = open(os.path.join(scratch, ".block-%d.log" % block.line), "w+b")
        proc = subprocess.Popen(argv, cwd=scratch, env=env, stdout=log,
                                stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                start_new_session=True)
        start = time.monotonic()
        stopped = set()
        status = None
        while status is None:
            try:
                status = proc.wait(timeout=0.1)
            except subprocess.TimeoutExpired:
                pass
            if status is None and block.stops:
                self.stop_named(proc.pid, block.stops, stopped)
            if status is None and time.monotonic() - start > limit:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
                status = "timeout after %g s" % limit
        self.stop_group(proc.pid)
        log.seek(0)
        output = log.read().decode("utf-8", "replace")
        log.close()
        return status, output

    @staticmethod
    def group_processes(pgid):
        """(pid, name, age in s) of the live processes of a group."""
        found = []
        ticks = os.sysconf("SC_CLK_TCK")
        uptime = float(open("/proc/uptime").read().split()[0])
        for entry in os.listdir("/proc"):
            if not entry.isdigit():
                continue
            try:
                stat = open("/proc/%s/stat" % entry).read()
            except OSError:
                continue
            name = stat[stat.index("(") + 1:stat.rindex(")")]
            fields = stat[stat.rindex(")") + 2:].split()
            if fields[0] == "Z" or int(fields[2]) != pgid:
                continue
            found.append((int(entry), name, uptime - int(fields[19]) / ticks))
        return found

    def stop_named(self, pgid, stops, stopped):
        for pid, name, age in self.group_processes(pgid):
            for _, prog, seconds in stops:
                if name == prog and age >= seconds and pid not in stopped:
                    stopped.add(pid)
                    try:
                        os.kill(pid, signal.SIGINT)
                    except ProcessLookupError:
                        pass

    def stop_group(self, pgid):
        """Stops what a block left running: SIGINT, then SIGKILL."""
        for sig, grace in ((signal.SIGINT, 10.0), (signal.SIGKILL, 5.0)):
            if not self.group_processes(pgid):
                return
            try:
                os.killpg(pgid, sig)
            except ProcessLookupError:
                return
            deadline = time.monotonic() + grace
            while self.group_processes(pgid) and time.monotonic() < deadline:
                try:
                    os.waitpid(-1, os.WNOHANG)
                except ChildProcessError:
                    pass
                time.sleep(0.05)

    def run_sh(self, block, scratch, env):
        code = DEFAULT_URL.sub(self.url, block.prelude + "\n" + block.code)
        # A program the runner stops with SIGINT may end as Ctrl-C ends it
        # (status 130, or 143 after SIGTERM); any other failure still counts.
        wrappers = "".join(
            '%s() { command %s "$@" || { s=$?; [ $s = 130 ] || [ $s = 143 ] '
            '|| return $s; }; }\n' % (name, name) for name, _, _ in block.stops)
        script = os.path.join(scratch, ".block-%d.sh" % block.line)
        with open(script, "w") as f:
            f.write("set -eo pipefail\n" + wrappers + code)
        return self.run_process(["bash", script], block, scratch, env)

    def run_lua(self, block, scratch, env):
        types = os.path.join(scratch, ".cache/mrsim/lua_types")
        os.makedirs(types, exist_ok=True)
        lcm_files = [os.path.join(ROOT, "lcmtypes/mrsim", f)
                     for f in sorted(os.listdir(os.path.join(ROOT, "lcmtypes/mrsim")))
                     if f.endswith(".lcm")]
        subprocess.run(["lcm-gen", "--lua", "--lpath", types] + lcm_files,
                       check=True, stdout=subprocess.DEVNULL)
        env = dict(env, LUA_PATH="%s/?.lua;%s/?/init.lua;;" % (types, types))
        script = os.path.join(scratch, ".block-%d.lua" % block.line)
        with open(script, "w") as f:
            f.write(block.prelude + "\n" + block.code)
        return self.run_process(["lua5.2", script], block, scratch, env)

    def dev_prefix(self):
        if self.cpp_prefix is None:
            prefix = os.path.join(self.scratch_root, ".prefix")
            subprocess.run(["cmake", "--install", self.build, "--prefix", prefix,
                            "--component", "development"], check=True,
                           stdout=subprocess.DEVNULL)
            self.cpp_prefix = prefix
        return self.cpp_prefix

    def run_cpp(self, block, scratch, env):
        project = os.path.join(scratch, ".cpp-%d" % block.line)
        os.makedirs(project, exist_ok=True)
        includes, body = [], []
        for line in (block.prelude + "\n" + block.code).splitlines():
            (includes if line.startswith("#include") else body).append(line)
        source = "\n".join(includes) + "\n\nint main() {\n" + "\n".join(
            "  " + l for l in body) + "\n  return 0;\n}\n"
        if re.search(r"\bint\s+main\s*\(", block.code):
            source = block.prelude + "\n" + block.code
        with open(os.path.join(project, "snippet.cc"), "w") as f:
            f.write(source)
        with open(os.path.join(project, "CMakeLists.txt"), "w") as f:
            f.write("cmake_minimum_required(VERSION 3.16)\nproject(snippet CXX)\n"
                    "set(CMAKE_CXX_STANDARD 17)\nfind_package(mrsim REQUIRED)\n"
                    "add_executable(snippet snippet.cc)\n"
                    "target_link_libraries(snippet PRIVATE mrsim::sim_core "
                    "mrsim::gait mrsim::optimizer mrsim::logger)\n")
        script = ("set -eo pipefail\ncmake -S %s -B %s/build -DCMAKE_PREFIX_PATH=%s "
                  "-DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF "
                  "-DCMAKE_BUILD_TYPE=Release >/dev/null\n"
                  "cmake --build %s/build -j2 >/dev/null\n%s/build/snippet\n" %
                  (project, project, self.dev_prefix(), project, project))
        path = os.path.join(scratch, ".block-%d.sh" % block.line)
        with open(path, "w") as f:
            f.write(script)
        return self.run_process(["bash", path], block, scratch, env)

    def run_python(self, block, scratch, env):
        package = os.path.join(self.build, "python")
        env = dict(env, PYTHONPATH=package)
        script = os.path.join(scratch, ".block-%d.py" % block.line)
        with open(script, "w") as f:
            f.write(block.prelude + "\n" + block.code)
        return self.run_process(["/usr/bin/python3", script], block, scratch, env)

    def why_not_run(self, block):
        if block.lang in TEXT_LANGS:
            return "text"
        if block.lang not in RUN_LANGS:
            return "unknown language '%s'" % block.lang
        if block.manual:
            return "manual: " + block.manual
        if block.root:
            if not self.args.slow:
                return "needs root (slow target)"
            if os.geteuid() != 0 or os.environ.get("MRSIM_DOCS_ROOT") != "1":
                return "needs root: run the slow target as root with MRSIM_DOCS_ROOT=1"
        if block.slow != self.args.slow:
            return "slow (slow target)" if block.slow else "fast target"
        if block.lang == "python" and not os.path.isdir(
                os.path.join(self.build, "python")):
            return "python: %s/python is not built" % self.build
        return None

    def run(self, files):
        parse_errors = []
        for path in files:
            blocks, errors = parse(path)
            parse_errors += errors
            scratch = None
            for block in blocks:
                if self.args.only and not block.where().startswith(self.args.only):
                    continue
                reason = self.why_not_run(block)
                if reason:
                    self.results.append((block, "not run", 0.0, reason))
                    continue
                if scratch is None:
                    scratch = self.scratch_for(path)
                env = self.env(scratch)
                start = time.monotonic()
                runner = {"sh": self.run_sh, "bash": self.run_sh,
                          "lua": self.run_lua, "cpp": self.run_cpp,
                          "python": self.run_python}[block.lang]
                try:
                    status, output = runner(block, scratch, env)
                except (OSError, subprocess.CalledProcessError) as e:
                    status, output = "runner error", str(e)
                seconds = time.monotonic() - start
                ok = status == block.exit
                verdict = "PASS" if ok else "FAIL"
                detail = "" if ok else "status %s, expected %d\n%s" % (
                    status, block.exit, output[-4000:])
                print("%s %s (%s, %.1f s)" % (verdict, block.where(), block.lang,
                                               seconds), flush=True)
                if not ok:
                    print("  " + detail.replace("\n", "\n  "), flush=True)
                self.results.append((block, verdict, seconds, detail))
        for error in parse_errors:
            print("ERROR " + error)
        passed = sum(1 for r in self.results if r[1] == "PASS")
        failed = sum(1 for r in self.results if r[1] == "FAIL")
        print("\nNot run:")
        for block, verdict, _, reason in self.results:
            if verdict == "not run" and reason not in ("text", "fast target"):
                print("  %s (%s): %s" % (block.where(), block.lang, reason))
        text = sum(1 for r in self.results if r[3] == "text")
        other = sum(1 for r in self.results if r[3] == "fast target")
        total = sum(r[2] for r in self.results)
        print("\ndocs runner: %d passed, %d failed, %d parse errors, %d text "
              "blocks, %d for the other target, %d not run; %.1f s" %
              (passed, failed, len(parse_errors), text, other,
               len(self.results) - passed - failed - text - other, total))
        if parse_errors:
            return 2
        return 1 if failed else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="*",
                        help="Markdown files (default: README.md docs/*.md)")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"),
                        help="the build folder (programs in BUILD/bin)")
    parser.add_argument("--slow", action="store_true",
                        help="run the blocks marked slow (and root) instead")
    parser.add_argument("--port", type=int, default=7993,
                        help="LCM port (plus MRSIM_TEST_PORT_OFFSET)")
    parser.add_argument("--scratch", help="scratch folder (default BUILD/docs_runner)")
    parser.add_argument("--only", help="run only blocks at FILE[:LINE]")
    args = parser.parse_args()
    files = [os.path.abspath(f) for f in args.files] or (
        [os.path.join(ROOT, "README.md")] +
        sorted(os.path.join(ROOT, "docs", f)
               for f in os.listdir(os.path.join(ROOT, "docs")) if f.endswith(".md")))
    if not os.path.isdir(os.path.join(args.build, "bin")):
        print("docs runner: %s/bin not found (build first)" % args.build,
              file=sys.stderr)
        return 2
    return Runner(args).run(files)


if __name__ == "__main__":
    sys.exit(main())
