#!/usr/bin/env python3
"""Generates the Python conversions of every LCM message from the .lcm files.

mrsim._core hands every message type the .lcm files define to Python and
back (mrsim.Node publishes and receives each of them): one generated C++
header with, for each struct,

- MessageToDict(msg): a dict holding every field (numbers as int/float/
  bool, strings as str, numeric arrays as numpy arrays, byte arrays as
  bytes, nested structs as dicts, arrays of them as lists);
- MessageFromDict(obj, &msg, where): the reverse; a field left out is zero
  or empty, a length member (num_joints) is the size of the arrays it
  sizes, and a value of the wrong type, a fixed array of the wrong size or
  a string or array beyond its `// max:` raises TypeError/ValueError
  naming the field, so nothing is published that receivers would drop;
- ConstName(&msg, value): the name of the integer const with that value;

plus AnyMessage (a std::variant of every type), kMessageTypeNames in the
same order, and MessageTypes(): every type's fields (name, type, dims,
max) and consts for Python (mrsim._core.message_types()). Hand-written
code (python/src/lcm_bindings.cc) adds meaning only where a field needs it.

  py_message_gen.py --output python_messages.h FILE.lcm...
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from wire_check_gen import PRIMITIVE_SIZE, LcmError, parse  # noqa: E402

CONST_RE = re.compile(r"\bconst\s+(\w+)\s+([^;]*);")
INTEGER_CONST = {"int8_t", "int16_t", "int32_t", "int64_t", "byte"}


def consts_of(path):
    """{struct name: [(type, NAME)]} of the consts in one .lcm file."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    found = {}
    for struct in re.finditer(r"\bstruct\s+(\w+)\s*\{(.*?)\}", text, re.S):
        items = []
        for const in CONST_RE.finditer(struct.group(2)):
            for part in const.group(2).split(","):
                name = part.split("=", 1)[0].strip()
                if not re.fullmatch(r"[A-Za-z_]\w*", name):
                    raise LcmError(f"{path}: const '{part.strip()}' in "
                                   f"{struct.group(1)}: expected NAME = VALUE")
                items.append((const.group(1), name))
        found[struct.group(1)] = items
    return found


def cpp(full):
    return "::" + full.replace(".", "::")


def short(type_name):
    return type_name.rsplit(".", 1)[-1]


def kind(m):
    if m.type == "boolean":
        return "Kind::kBool"
    if m.type == "byte" and m.dims:
        return "Kind::kBytes"
    return "Kind::kPlain"


class Generator:
    def __init__(self, structs, consts):
        self.structs = sorted(structs, key=lambda s: s.full)
        self.by_name = {s.full: s for s in structs}
        self.consts = consts
        for s in self.structs:
            for m in s.members:
                if m.type not in PRIMITIVE_SIZE and m.type != "string" and \
                        m.type not in self.by_name:
                    raise LcmError(f"{m.where}: unknown type {m.type}")
                for level, d in enumerate(m.dims):
                    if isinstance(d, str) and level > 0:
                        raise LcmError(
                            f"{m.where}: {m.name}: a variable dimension "
                            "after the first is not supported by "
                            "py_message_gen.py")

    @staticmethod
    def lengths(s):
        """{length member: [arrays it sizes]} of a struct."""
        out = {}
        for m in s.members:
            if m.dims and isinstance(m.dims[0], str):
                out.setdefault(m.dims[0], []).append(m)
        return out

    def limit_of(self, s, m):
        """Limits{string bytes, elements} for member m of s."""
        string_max = m.limit if m.type == "string" and m.limit else -1
        count_max = -1
        if m.dims and isinstance(m.dims[0], str):
            ref = next(o for o in s.members if o.name == m.dims[0])
            count_max = ref.limit if ref.limit is not None else -1
        return f"Limits{{{string_max}, {count_max}}}"

    def to_dict(self, s):
        out = [f"inline pybind11::dict MessageToDict(const {s.name}& m) {{",
               "  pybind11::dict d;"]
        for m in s.members:
            out.append(f'  d["{m.name}"] = ToPy<{kind(m)}>(m.{m.name});')
        out += ["  return d;", "}"]
        return out

    def from_dict(self, s):
        lengths = self.lengths(s)
        names = ", ".join(f'"{m.name}"' for m in s.members)
        out = [
            f"inline void MessageFromDict(pybind11::handle obj, {s.name}* m,",
            "                            const std::string& where) {",
            f"  FieldReader r(obj, where, {{{names}}});",
        ]
        for m in s.members:
            if m.name in lengths:
                continue
            out.append(f'  r.Take<{kind(m)}>("{m.name}", &m->{m.name}, '
                       f"{self.limit_of(s, m)});")
        for name, arrays in lengths.items():
            sizes = ", ".join(f'{{"{a.name}", m->{a.name}.size()}}'
                              for a in arrays)
            out.append(f'  r.Length("{name}", &m->{name}, {{{sizes}}});')
        out.append("}")
        return out

    def const_name(self, s):
        out = [f"inline const char* ConstName(const {s.name}*, "
               "int64_t value) {"]
        for type_name, name in self.consts.get(s.name, []):
            if type_name in INTEGER_CONST:
                out.append(f"  if (value == {s.name}::{name}) "
                           f'return "{name}";')
        out += ["  (void)value;", "  return nullptr;", "}"]
        return out

    def describe(self, s):
        out = ["  {", "    pybind11::list fields;"]
        for m in s.members:
            dims = ", ".join(f'pybind11::str("{d}")' if isinstance(d, str)
                             else f"pybind11::int_({d})" for d in m.dims)
            limit = ("pybind11::none()" if m.limit is None
                     else f"pybind11::int_({m.limit})")
            out.append(f'    fields.append(Field("{m.name}", '
                       f'"{short(m.type)}", pybind11::make_tuple({dims}), '
                       f"{limit}));")
        out.append("    pybind11::dict consts;")
        for _, name in self.consts.get(s.name, []):
            out.append(f'    consts["{name}"] = {cpp(s.full)}::{name};')
        out += [
            "    pybind11::dict t;",
            '    t["fields"] = fields;',
            '    t["consts"] = consts;',
            f'    types["{s.name}"] = t;',
            "  }",
        ]
        return out

    def header(self):
        out = [
            "// Generated by lcmtypes/py_message_gen.py from",
            "// lcmtypes/mrsim/*.lcm; do not edit. Every message type to",
            "// Python and back (see the script's doc); the helpers are",
            "// python/src/message_convert.h.",
            "#pragma once",
            "",
            "#include <pybind11/pybind11.h>",
            "",
            "#include <cstdint>",
            "#include <string>",
            "#include <variant>",
            "",
        ]
        for s in self.structs:
            out.append(f'#include "{s.full.replace(".", "/")}.hpp"')
        out += ['#include "python/src/message_convert.h"', ""]
        packages = sorted({s.package for s in self.structs})
        if packages != ["mrsim"]:
            raise LcmError("py_message_gen.py: every type must be in "
                           "package mrsim")
        # In the messages' namespace, so that the helpers' templates find
        # them by argument-dependent lookup.
        out += ["namespace mrsim {", ""]
        out.append("using python::messages::FieldReader;")
        out.append("using python::messages::Kind;")
        out.append("using python::messages::Limits;")
        out.append("using python::messages::ToPy;")
        out.append("")
        for s in self.structs:
            out.append(f"pybind11::dict MessageToDict(const {s.name}& m);")
            out.append("void MessageFromDict(pybind11::handle obj, "
                       f"{s.name}* m,")
            out.append("                     const std::string& where);")
        out.append("")
        for s in self.structs:
            out += self.to_dict(s) + [""] + self.from_dict(s) + [""]
            out += self.const_name(s) + [""]
        names = ", ".join(cpp(s.full) for s in self.structs)
        out += [
            "// Every message type, in the order of kMessageTypeNames.",
            f"using AnyMessage = std::variant<{names}>;",
            "inline constexpr const char* kMessageTypeNames[] = {",
        ]
        out += [f'    "{s.name}",' for s in self.structs]
        out += [
            "};",
            "",
            "// {type: {\"fields\": [{name, type, dims, max}],",
            "//         \"consts\": {NAME: value}}}.",
            "inline pybind11::dict MessageTypes() {",
            "  using python::messages::Field;",
            "  pybind11::dict types;",
        ]
        for s in self.structs:
            out += self.describe(s)
        out += ["  return types;", "}", "", "}  // namespace mrsim"]
        return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--output", required=True)
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    try:
        structs, consts = [], {}
        for path in args.files:
            structs += parse(path)
            consts.update(consts_of(path))
        text = Generator(structs, consts).header()
    except (LcmError, OSError, ValueError) as e:
        print(f"py_message_gen: {e}", file=sys.stderr)
        return 2
    try:
        with open(args.output, encoding="utf-8") as f:
            if f.read() == text:
                return 0  # unchanged: nothing that includes it rebuilds
    except OSError:
        pass
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    with open(args.output, "w", encoding="utf-8") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
