#!/usr/bin/env python3
"""Generates JSON Schemas and C++ JSON writers for the LCM messages.

Foxglove, PlotJuggler and MCAP files take messages as JSON described by a
JSON Schema (message encoding `json`, schema encoding `jsonschema`). Both
come from the .lcm files, so a new field appears in them without anyone
writing a line: one schema per struct (nested structs inlined, fixed
arrays with their length, the struct's comment as its description) and one
`WriteJson(const T&, JsonWriter&)` per struct, plus a table of every type by
fingerprint that decodes a raw message with the checked decode
(lcmtypes/runtime/decode.h) and writes it as JSON.

Member names are the .lcm names; numbers are JSON numbers (NaN and the
infinities, which JSON has no word for, are null: the schema says
number, as Foxglove reads it), booleans true/false,
strings UTF-8 (bytes that are not become U+FFFD).

  json_message_gen.py --header OUT.hpp --source OUT.cc FILE.lcm...
  json_message_gen.py --schema TYPE FILE.lcm...   (one schema, for docs)
"""
import argparse
import json
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from wire_check_gen import LcmError, parse  # noqa: E402

INTEGER = {"int8_t", "int16_t", "int32_t", "int64_t", "byte"}
FLOAT = {"float", "double"}


def struct_comments(path):
    """The comment block just above each `struct NAME` of a file."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    out = {}
    for i, line in enumerate(lines):
        found = re.match(r"\s*struct\s+(\w+)", line)
        if not found:
            continue
        block = []
        j = i - 1
        while j >= 0 and lines[j].strip().startswith("//"):
            block.insert(0, lines[j].strip()[2:].strip())
            j -= 1
        out[found.group(1)] = " ".join(block)
    return out


class Generator:
    def __init__(self, files):
        self.structs = []
        self.comments = {}
        for path in files:
            found = parse(path)
            comments = struct_comments(path)
            for s in found:
                self.comments[s.full] = comments.get(s.name, "")
            self.structs += found
        self.by_name = {s.full: s for s in self.structs}
        for s in self.structs:
            for m in s.members:
                if m.type not in INTEGER | FLOAT | {"boolean", "string"} and \
                        m.type not in self.by_name:
                    raise LcmError(f"{m.where}: unknown type {m.type}")

    # ---- JSON Schema ----
    def element_schema(self, type_name):
        if type_name in INTEGER:
            return {"type": "integer"}
        if type_name in FLOAT:
            return {"type": "number"}  # NaN and infinities are written null
        if type_name == "boolean":
            return {"type": "boolean"}
        if type_name == "string":
            return {"type": "string"}
        return self.struct_schema(self.by_name[type_name], top=False)

    def member_schema(self, m):
        schema = self.element_schema(m.type)
        for d in reversed(m.dims):
            array = {"type": "array", "items": schema}
            if isinstance(d, int):
                array["minItems"] = d
                array["maxItems"] = d
            else:
                array["description"] = f"{d} elements"
            schema = array
        return schema

    def struct_schema(self, s, top=True):
        schema = {}
        if top:
            schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
        schema["title"] = s.full
        if self.comments.get(s.full):
            schema["description"] = self.comments[s.full]
        schema["type"] = "object"
        schema["properties"] = {m.name: self.member_schema(m)
                                for m in s.members}
        schema["required"] = [m.name for m in s.members]
        return schema

    # ---- C++ ----
    def write_value(self, type_name, expr, indent):
        pad = " " * indent
        if type_name in INTEGER:
            cast = "static_cast<int64_t>" if type_name != "int64_t" else ""
            return [f"{pad}out.Int({cast}({expr}));"]
        if type_name in FLOAT:
            return [f"{pad}out.Double({expr});"]
        if type_name == "boolean":
            return [f"{pad}out.Bool({expr} != 0);"]
        if type_name == "string":
            return [f"{pad}out.String({expr});"]
        return [f"{pad}WriteJson({expr}, out);"]

    def write_member(self, m, indent, depth=0, expr=None):
        pad = " " * indent
        expr = expr or f"m.{m.name}"
        if depth == len(m.dims):
            return self.write_value(m.type, expr, indent)
        var = f"e{depth}"
        dim = m.dims[depth]
        if isinstance(dim, str):
            # As many as the length member says: lcm-gen's decode leaves a
            # vector as it was when its length is 0, so a message decoded
            # into a reused one (ToJson's) would otherwise write the last
            # message's elements (a camera's answer without targets after
            # a controller's command).
            loop = [f"{pad}  const size_t n{depth} = std::min<size_t>(",
                    f"{pad}      static_cast<size_t>(std::max<int64_t>(0, "
                    f"m.{dim})), std::size({expr}));",
                    f"{pad}  for (size_t i{depth} = 0; i{depth} < n{depth}; "
                    f"++i{depth}) {{",
                    f"{pad}    const auto& {var} = {expr}[i{depth}];"]
        else:
            loop = [f"{pad}  for (const auto& {var} : {expr}) {{"]
        lines = [f"{pad}out.Raw(\"[\");", f"{pad}{{",
                 f"{pad}  bool first{depth} = true;"] + loop + [
                 f"{pad}    if (!first{depth}) out.Raw(\",\");",
                 f"{pad}    first{depth} = false;"]
        lines += self.write_member(m, indent + 4, depth + 1, var)
        lines += [f"{pad}  }}", f"{pad}}}", f"{pad}out.Raw(\"]\");"]
        return lines

    def ordered(self):
        done, out = set(), []

        def visit(name):
            if name in done:
                return
            done.add(name)
            for m in self.by_name[name].members:
                if m.type in self.by_name:
                    visit(m.type)
            out.append(self.by_name[name])
        for s in self.structs:
            visit(s.full)
        return out

    @staticmethod
    def cpp_type(s):
        return s.full.replace(".", "::")

    def header(self):
        out = ["// Generated by lcmtypes/json_message_gen.py from the .lcm files: "
               "do not edit.",
               "// Every mrsim message as JSON, with its JSON Schema "
               "(docs/logger.md, \"MCAP\").",
               "#pragma once", "", "#include <cstddef>", "#include <cstdint>",
               "#include <vector>", "",
               "#include \"lcmtypes/json/json_writer.h\""]
        for s in self.structs:
            out.append(f"#include \"{s.package}/{s.name}.hpp\"")
        out += ["", "namespace mrsim {", "",
                "// One message type: its name, fingerprint, JSON Schema "
                "and a function that",
                "// checks and decodes a raw message (fingerprint first; a "
                "signature trailer is",
                "// allowed) and writes it as JSON, giving its `seq` when it "
                "has one. It returns",
                "// false, writing nothing, for bytes that are not such a "
                "message.",
                "struct MessageJsonType {",
                "  const char* name;  // \"mrsim.robot_state_t\"",
                "  int64_t fingerprint;",
                "  const char* schema;  // JSON Schema text",
                "  bool has_seq;  // a top-level int64_t seq member",
                "  bool (*to_json)(const void* data, size_t size, "
                "JsonWriter& out,",
                "                  int64_t* seq);",
                "};", "",
                "// Every type of lcmtypes/mrsim, in file order.",
                "const std::vector<MessageJsonType>& MessageJsonTypes();",
                "// The type with this fingerprint, or nullptr.",
                "const MessageJsonType* FindMessageJsonType(int64_t "
                "fingerprint);", ""]
        for s in self.structs:
            out.append(f"void WriteJson(const {self.cpp_type(s)}& m, "
                       "JsonWriter& out);")
        out += ["", "}  // namespace mrsim", ""]
        return "\n".join(out)

    def source(self, header_name):
        out = ["// Generated by lcmtypes/json_message_gen.py: do not edit.",
               f"#include \"mrsim/{header_name}\"", "",
               "#include <algorithm>", "#include <iterator>", "",
               "#include \"lcmtypes/runtime/decode.h\"", "",
               "namespace mrsim {", ""]
        for s in self.ordered():
            out.append(f"void WriteJson(const {self.cpp_type(s)}& m, "
                       "JsonWriter& out) {")
            for i, m in enumerate(s.members):
                sep = "{" if i == 0 else ","
                out.append(f"  out.Raw(\"{sep}\\\"{m.name}\\\":\");")
                out += self.write_member(m, 2)
            if not s.members:
                out.append("  out.Raw(\"{\");")
            out += ["  out.Raw(\"}\");", "}", ""]
        out = merge_raw(out)
        out += ["namespace {", ""]
        for s in self.structs:
            has_seq = any(m.name == "seq" and m.type == "int64_t" and
                          not m.dims for m in s.members)
            fn = s.full.replace(".", "_")
            out += [f"bool {fn}_ToJson(const void* data, size_t size, "
                    "JsonWriter& out,",
                    f"    int64_t* seq) {{",
                    "  // Reused: its vectors keep their room from one "
                    "message to the next.",
                    f"  thread_local {self.cpp_type(s)} m;",
                    "  if (!DecodeMessage(data, size, &m)) return false;",
                    "  WriteJson(m, out);",
                    f"  if (seq != nullptr) *seq = {'m.seq' if has_seq else '0'};",
                    "  return true;", "}", ""]
        out += ["}  // namespace", "",
                "const std::vector<MessageJsonType>& MessageJsonTypes() {",
                "  static const std::vector<MessageJsonType> types = {"]
        for s in self.structs:
            has_seq = any(m.name == "seq" and m.type == "int64_t" and
                          not m.dims for m in s.members)
            schema = json.dumps(self.struct_schema(s), separators=(",", ":"))
            fn = s.full.replace(".", "_")
            out += [f"      {{\"{s.full}\", {self.cpp_type(s)}::getHash(),",
                    f"       R\"json({schema})json\",",
                    f"       {'true' if has_seq else 'false'}, &{fn}_ToJson}},"]
        out += ["  };", "  return types;", "}", "",
                "const MessageJsonType* FindMessageJsonType(int64_t "
                "fingerprint) {",
                "  for (const MessageJsonType& t : MessageJsonTypes()) {",
                "    if (t.fingerprint == fingerprint) return &t;",
                "  }",
                "  return nullptr;", "}", "", "}  // namespace mrsim", ""]
        return "\n".join(out)


RAW = re.compile(r'^(\s*)out\.Raw\("(.*)"\);$')


def merge_raw(lines):
    """Adjacent literal writes at one level become one."""
    out = []
    for line in lines:
        here = RAW.match(line)
        before = RAW.match(out[-1]) if out else None
        if here and before and here.group(1) == before.group(1):
            out[-1] = f'{here.group(1)}out.Raw("{before.group(2)}{here.group(2)}");'
        else:
            out.append(line)
    return out


def write_if_changed(path, text):
    try:
        with open(path, encoding="utf-8") as f:
            if f.read() == text:
                return
    except OSError:
        pass
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--header")
    parser.add_argument("--source")
    parser.add_argument("--schema", help="print the JSON Schema of one type")
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    try:
        gen = Generator(args.files)
    except (LcmError, OSError, ValueError) as e:
        print(f"json_message_gen: {e}", file=sys.stderr)
        return 2
    if args.schema:
        s = gen.by_name.get(args.schema)
        if s is None:
            print(f"json_message_gen: no type {args.schema}", file=sys.stderr)
            return 2
        print(json.dumps(gen.struct_schema(s), indent=2))
        return 0
    if not args.header or not args.source:
        print("json_message_gen: --header and --source are needed",
              file=sys.stderr)
        return 2
    write_if_changed(args.header, gen.header())
    write_if_changed(args.source, gen.source(os.path.basename(args.header)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
