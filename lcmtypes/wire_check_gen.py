#!/usr/bin/env python3
"""Generates bounds checks for LCM messages from their .lcm definitions.

lcm-gen's C++ decode trusts every length it reads (a string length of
INT32_MIN reads 2 GB past the buffer, an array length of 2^31 allocates
16 GB), so every received message is first walked by the check this
script generates: the fingerprint, every string length (>= 1 with its NUL,
within the bytes left and the field's maximum) and every array length
(>= 0, within its maximum, count * smallest element within the bytes left),
nested types recursively, and nothing left over. Only then is lcm-gen's
decode run. The wire format and fingerprints stay lcm-gen's.

Maxima are declared once, in the .lcm files, by a trailing comment on the
member: `string robot;  // max: 256` (bytes of each string, without the
NUL) and `int32_t num_modules;  // max: 4096` (elements of every array
sized by that member). A string or a length member without one is an error,
so a new message cannot forget its limits.

Units are declared the same way, `double force;  // unit: N` ("1": a
number without a unit), and --units-output writes them as a C++ table
(mrsim/field_units.hpp) that the logger's column units are taken from.

  wire_check_gen.py --output mrsim/wire_check.hpp FILE.lcm...
  wire_check_gen.py --output ... --units-output mrsim/field_units.hpp FILE.lcm...
  wire_check_gen.py --markdown FILE.lcm...   (the limits table for docs)
  wire_check_gen.py --check-doc DOC.md FILE.lcm...   (exit 1 if DOC's
      table between the limits markers differs; --update-doc rewrites it)
"""
import argparse
import difflib
import re
import sys

PRIMITIVE_SIZE = {
    "int8_t": 1, "byte": 1, "boolean": 1, "int16_t": 2, "int32_t": 4,
    "float": 4, "int64_t": 8, "double": 8,
}
INTEGER = {"int8_t", "byte", "int16_t", "int32_t", "int64_t"}
MAX_RE = re.compile(r"//.*?\bmax:\s*(\d+)")
# `// unit: N m`, up to the end of the comment or a following `max:`.
UNIT_RE = re.compile(r"//.*?\bunit:\s*(.*?)\s*(?:[;,]?\s*\bmax:.*)?$")


class LcmError(Exception):
    pass


class Member:
    def __init__(self, type_name, name, dims, limit, where, unit=None):
        self.type = type_name  # primitive, "string" or full struct name
        self.name = name
        self.dims = dims  # list of int (fixed) or str (length member)
        self.limit = limit  # from `// max: N`, or None
        self.where = where
        self.unit = unit  # from `// unit: U`, or None


class Struct:
    def __init__(self, package, name):
        self.package = package
        self.name = name
        self.members = []

    @property
    def full(self):
        return self.package + "." + self.name if self.package else self.name


def tokenize(text, path, units=None):
    """Tokens with their line, and the `max:` annotation of each line (and
    the `unit:` one into `units`, when given)."""
    limits = {}
    tokens = []
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text,
                  flags=re.S)
    for number, line in enumerate(text.split("\n"), start=1):
        found = MAX_RE.search(line)
        if found:
            limits[number] = int(found.group(1))
        found = UNIT_RE.search(line)
        if found and units is not None:
            if not found.group(1):
                raise LcmError(f"{path}:{number}: 'unit:' without a unit")
            units[number] = found.group(1)
        code = line.split("//", 1)[0]
        for tok in re.findall(r"[A-Za-z0-9_.+-]+|[;{}\[\]=,]", code):
            tokens.append((tok, number))
    return tokens, limits


def parse(path):
    units = {}
    with open(path, encoding="utf-8") as f:
        tokens, limits = tokenize(f.read(), path, units)
    pos = 0
    package = ""
    structs = []

    def take(expected=None):
        nonlocal pos
        if pos >= len(tokens):
            raise LcmError(f"{path}: unexpected end, expected {expected}")
        tok, line = tokens[pos]
        if expected is not None and tok != expected:
            raise LcmError(f"{path}:{line}: expected '{expected}', got '{tok}'")
        pos += 1
        return tok, line

    while pos < len(tokens):
        tok, line = take()
        if tok == "package":
            package, _ = take()
            take(";")
        elif tok == "struct":
            name, _ = take()
            s = Struct(package, name)
            take("{")
            while tokens[pos][0] != "}":
                tok, line = take()
                if tok == "const":
                    while take()[0] != ";":
                        pass
                    continue
                type_name = tok
                while True:
                    name, line = take()
                    dims = []
                    while tokens[pos][0] == "[":
                        take("[")
                        d, _ = take()
                        dims.append(int(d) if d.isdigit() else d)
                        take("]")
                    if type_name not in PRIMITIVE_SIZE and type_name != "string" \
                            and "." not in type_name:
                        full = package + "." + type_name if package else type_name
                    else:
                        full = type_name
                    s.members.append(Member(full, name, dims, limits.get(line),
                                            f"{path}:{line}", units.get(line)))
                    sep, _ = take()
                    if sep == ";":
                        break
                    if sep != ",":
                        raise LcmError(f"{path}:{line}: expected ';' or ','")
            take("}")
            structs.append(s)
        else:
            raise LcmError(f"{path}:{line}: unexpected '{tok}'")
    return structs


def c_name(full):
    return full.replace(".", "_")


class Generator:
    def __init__(self, structs):
        self.by_name = {s.full: s for s in structs}
        self.min_size_cache = {}
        self.check()

    def check(self):
        for s in self.by_name.values():
            lengths = {d for m in s.members for d in m.dims if isinstance(d, str)}
            seen = {}
            for m in s.members:
                if m.type not in PRIMITIVE_SIZE and m.type != "string" and \
                        m.type not in self.by_name:
                    raise LcmError(f"{m.where}: unknown type {m.type}")
                if m.type == "string" and m.limit is None:
                    raise LcmError(f"{m.where}: string {m.name} needs a "
                                   "'// max: N' comment (bytes)")
                for d in m.dims:
                    if isinstance(d, str):
                        ref = seen.get(d)
                        if ref is None or ref.type not in INTEGER or ref.dims:
                            raise LcmError(f"{m.where}: length {d} is not an "
                                           "earlier integer member")
                if m.name in lengths and m.limit is None:
                    raise LcmError(f"{m.where}: length member {m.name} needs a "
                                   "'// max: N' comment (elements)")
                seen[m.name] = m

    def fixed_size(self, type_name):
        """Encoded bytes of a type whose size never varies, else None."""
        if type_name in PRIMITIVE_SIZE:
            return PRIMITIVE_SIZE[type_name]
        if type_name == "string":
            return None
        total = 0
        for m in self.by_name[type_name].members:
            size = self.fixed_size(m.type)
            if size is None or any(isinstance(d, str) for d in m.dims):
                return None
            for d in m.dims:
                size *= d
            total += size
        return total

    def min_size(self, type_name):
        """The fewest bytes an element of the type can take."""
        if type_name in PRIMITIVE_SIZE:
            return PRIMITIVE_SIZE[type_name]
        if type_name == "string":
            return 5  # int32 length and the NUL
        if type_name not in self.min_size_cache:
            total = 0
            for m in self.by_name[type_name].members:
                if any(isinstance(d, str) for d in m.dims):
                    continue
                size = self.min_size(m.type)
                for d in m.dims:
                    size *= d
                total += size
            self.min_size_cache[type_name] = total
        return self.min_size_cache[type_name]

    def element(self, m, field, indent):
        """Code checking one element (no dimensions) of member m."""
        pad = " " * indent
        if m.type == "string":
            return [f'{pad}if (!r.String({m.limit}, "{field}")) return false;']
        size = self.fixed_size(m.type)
        if size is not None:
            return [f'{pad}if (!r.Skip({size}, "{field}")) return false;']
        return [f"{pad}if (!Check_{c_name(m.type)}(r)) return false;"]

    def member(self, s, m):
        field = f"{s.name}.{m.name}"
        lines = []
        if not m.dims:
            if any(m.name in (d for d in o.dims) for o in s.members):
                size = PRIMITIVE_SIZE[m.type]
                return [f'  if (!r.Integer({size}, &{m.name}, "{field}")) '
                        "return false;"]
            return self.element(m, field, 2)
        size = self.fixed_size(m.type)
        if size is not None and all(isinstance(d, int) for d in m.dims):
            total = size
            for d in m.dims:
                total *= d
            return [f'  if (!r.Skip({total}, "{field}")) return false;']
        # Each dimension: its count checked before anything is walked.
        indent = 2
        for level, d in enumerate(m.dims):
            pad = " " * indent
            count = str(d)
            if isinstance(d, str):
                limit = next(o.limit for o in s.members if o.name == d)
                element_min = self.min_size(m.type)
                for later in m.dims[level + 1:]:
                    element_min *= later if isinstance(later, int) else 0
                lines.append(f'{pad}if (!r.Count({d}, {limit}, {element_min}, '
                             f'"{field}")) return false;')
            last = level == len(m.dims) - 1
            if last and size is not None:
                lines.append(f"{pad}if (!r.Skip(static_cast<size_t>({count}) * "
                             f'{size}, "{field}")) return false;')
                break
            var = f"i{level}"
            lines.append(f"{pad}for (int64_t {var} = 0; {var} < {count}; "
                         f"++{var}) {{")
            indent += 2
            if last:
                lines += self.element(m, field, indent)
        while indent > 2:
            indent -= 2
            lines.append(" " * indent + "}")
        return lines

    def struct(self, s):
        out = [f"// {s.full}",
               f"inline bool Check_{c_name(s.full)}(WireReader& r) {{"]
        size = self.fixed_size(s.full)
        if size is not None:
            out.append(f'  return r.Skip({size}, "{s.name}");')
            out.append("}")
            return out
        lengths = {d for m in s.members for d in m.dims if isinstance(d, str)}
        for name in sorted(lengths):
            out.append(f"  int64_t {name} = 0;")
        for m in s.members:
            out += self.member(s, m)
        out.append("  return true;")
        out.append("}")
        return out

    def needs_clear(self, full, seen=None):
        """True when a struct holds a length-counted array, itself or in a
        member struct."""
        seen = seen or set()
        if full in seen:
            return False
        seen.add(full)
        for m in self.by_name[full].members:
            if any(isinstance(d, str) for d in m.dims):
                return True
            if m.type in self.by_name and self.needs_clear(m.type, seen):
                return True
        return False

    def clear(self, s):
        """ClearEmpty_<type>: lcm-gen's decode leaves an array as it was
        when its length is 0, so a message decoded into a reused one would
        keep the last message's elements; this empties them."""
        cpp = "::" + s.full.replace(".", "::")
        out = [f"inline void ClearEmpty_{c_name(s.full)}({cpp}& m) {{"]
        for m in s.members:
            nested = m.type in self.by_name and self.needs_clear(m.type)
            if m.dims and isinstance(m.dims[0], str):
                out.append(f"  if (m.{m.dims[0]} <= 0) m.{m.name}.clear();")
            if nested and m.dims:
                out.append(f"  for (auto& e : m.{m.name}) "
                           f"ClearEmpty_{c_name(m.type)}(e);")
            elif nested:
                out.append(f"  ClearEmpty_{c_name(m.type)}(m.{m.name});")
        if len(out) == 1:
            out.append("  (void)m;")
        out.append("}")
        return out

    def order(self):
        done, result = set(), []

        def visit(name):
            if name in done:
                return
            done.add(name)
            for m in self.by_name[name].members:
                if m.type in self.by_name:
                    visit(m.type)
            result.append(self.by_name[name])

        for name in sorted(self.by_name):
            visit(name)
        return result

    def header(self):
        out = [
            "// Generated by lcmtypes/wire_check_gen.py from lcmtypes/mrsim/*.lcm;",
            "// do not edit. CheckWire<T>(data, size, error) is true when the",
            "// bytes are one whole T whose every length lcm-gen's decode may",
            "// trust (see lcmtypes/runtime/wire_reader.h).",
            "#pragma once",
            "",
            "#include <cstddef>",
            "#include <cstdint>",
            "",
            '#include "lcmtypes/runtime/wire_reader.h"',
        ]
        for s in sorted(self.by_name.values(), key=lambda s: s.full):
            out.append(f'#include "{s.full.replace(".", "/")}.hpp"')
        out += ["", "namespace mrsim {", "namespace wire_check {", ""]
        for s in self.order():
            out += self.struct(s)
            out.append("")
            out += self.clear(s)
            out.append("")
        out += ["}  // namespace wire_check", ""]
        for s in sorted(self.by_name.values(), key=lambda s: s.full):
            cpp = "::" + s.full.replace(".", "::")
            out += [
                "template <>",
                f"inline bool CheckWire<{cpp}>(const void* data, size_t size,",
                "                             WireError* error) {",
                "  WireReader r(static_cast<const uint8_t*>(data), size, error);",
                f'  return r.Fingerprint({cpp}::getHash(), "{s.name}") &&',
                f"         wire_check::Check_{c_name(s.full)}(r) && "
                f'r.AtEnd("{s.name}");',
                "}",
                "template <>",
                f"inline void ClearEmptyArrays<{cpp}>({cpp}* msg) {{",
                f"  wire_check::ClearEmpty_{c_name(s.full)}(*msg);",
                "}",
                "",
            ]
        out.append("}  // namespace mrsim")
        return "\n".join(out) + "\n"

    def units_header(self):
        out = [
            "// Generated by lcmtypes/wire_check_gen.py from the `// unit:`",
            "// comments in lcmtypes/mrsim/*.lcm; do not edit. The unit of each",
            "// annotated field (\"1\": a number without a unit).",
            "#pragma once",
            "",
            "#include <cstring>",
            "",
            "namespace mrsim {",
            "",
            "struct LcmFieldUnit {",
            "  const char* type;   // \"mrsim.pose_t\"",
            "  const char* field;  // \"position\"",
            "  const char* unit;   // \"m\"",
            "};",
            "",
            "inline constexpr LcmFieldUnit kLcmFieldUnits[] = {",
        ]
        for s in sorted(self.by_name.values(), key=lambda s: s.full):
            for m in s.members:
                if m.unit is not None:
                    unit = m.unit.replace("\\", "\\\\").replace('"', '\\"')
                    out.append(f'    {{"{s.full}", "{m.name}", "{unit}"}},')
        out += [
            "};",
            "",
            "// The unit of `type`'s member `field`, or nullptr when its .lcm",
            "// file declares none.",
            "inline const char* FindLcmFieldUnit(const char* type,",
            "                                    const char* field) {",
            "  for (const LcmFieldUnit& u : kLcmFieldUnits) {",
            "    if (std::strcmp(u.type, type) == 0 &&",
            "        std::strcmp(u.field, field) == 0) {",
            "      return u.unit;",
            "    }",
            "  }",
            "  return nullptr;",
            "}",
            "",
            "}  // namespace mrsim",
        ]
        return "\n".join(out) + "\n"

    def markdown(self):
        out = ["| message | field | maximum |", "|---|---|---|"]
        for s in sorted(self.by_name.values(), key=lambda s: s.full):
            for m in s.members:
                if m.limit is None:
                    continue
                if m.type == "string":
                    what = f"{m.limit} bytes" + (" each" if m.dims else "")
                else:
                    arrays = [o.name for o in s.members if m.name in o.dims]
                    what = f"{m.limit} elements ({', '.join(arrays)})"
                out.append(f"| {s.name} | {m.name} | {what} |")
        return "\n".join(out) + "\n"


DOC_BEGIN = "<!-- limits table: generated by lcmtypes/wire_check_gen.py " \
    "--update-doc; do not edit -->"
DOC_END = "<!-- end of limits table -->"


def doc_table(doc_path, table, update):
    """Compares (or with update, replaces) the table between the markers.

    Returns the error text, or None when the document matches."""
    with open(doc_path, encoding="utf-8") as f:
        text = f.read()
    begin = text.find(DOC_BEGIN)
    end = text.find(DOC_END)
    if begin < 0 or end < begin:
        return f"{doc_path}: no '{DOC_BEGIN}' ... '{DOC_END}' markers"
    start = begin + len(DOC_BEGIN) + 1
    old = text[start:end]
    if old == table:
        return None
    if update:
        with open(doc_path, "w", encoding="utf-8") as f:
            f.write(text[:start] + table + text[end:])
        return None
    line = text.count("\n", 0, start) + 1
    diff = "".join(difflib.unified_diff(
        old.splitlines(True), table.splitlines(True),
        f"{doc_path} (line {line})", "the .lcm files' limits"))
    return (f"{doc_path}:{line}: the limits table differs from the .lcm "
            "files' `// max:` comments; run lcmtypes/wire_check_gen.py "
            f"--update-doc {doc_path} lcmtypes/mrsim/*.lcm\n{diff}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--output")
    parser.add_argument("--units-output")
    parser.add_argument("--markdown", action="store_true")
    parser.add_argument("--check-doc", metavar="DOC")
    parser.add_argument("--update-doc", metavar="DOC")
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    try:
        structs = [s for path in args.files for s in parse(path)]
        gen = Generator(structs)
    except (LcmError, OSError, ValueError) as e:
        print(f"wire_check_gen: {e}", file=sys.stderr)
        return 2
    if args.markdown:
        sys.stdout.write(gen.markdown())
        return 0
    if args.check_doc or args.update_doc:
        try:
            error = doc_table(args.check_doc or args.update_doc,
                              gen.markdown(), bool(args.update_doc))
        except OSError as e:
            error = str(e)
        if error:
            print(f"wire_check_gen: {error}", file=sys.stderr)
            return 1
        return 0
    if not args.output:
        parser.error("one of --output, --markdown, --check-doc, --update-doc")
    write_if_changed(args.output, gen.header())
    if args.units_output:
        write_if_changed(args.units_output, gen.units_header())
    return 0


def write_if_changed(path, text):
    """Unchanged text keeps the file's time: nothing that includes it
    rebuilds."""
    try:
        with open(path, encoding="utf-8") as f:
            if f.read() == text:
                return
    except OSError:
        pass
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


if __name__ == "__main__":
    sys.exit(main())
