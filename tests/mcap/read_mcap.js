// Reads an MCAP file with the format's reference reader (@mcap/core) and
// prints what it found as one line of JSON, for the tests in this folder.
//
//   node read_mcap.js indexed FILE   open through the summary (chunk indexes),
//                                    every chunk CRC-checked, the data
//                                    section's CRC and the summary's too
//   node read_mcap.js stream FILE    read record by record from the start, as
//                                    a reader does with a file whose writer
//                                    died: up to the last whole record
//   node read_mcap.js same A B       both files indexed; every message of a
//                                    topic and seq in both compared as values
//
// Output: {"channels": {topic: {"count", "schema", "encoding", "seqs"}},
//          "statistics": ..., "complete": bool}; for "same":
// {"compared": n, "differ": n, "first_difference": text}. A JSON message
// must parse as JSON and hold every property its schema requires; a
// protobuf one must decode with protobufjs from its schema's
// FileDescriptorSet (as Foxglove does); otherwise it exits 1 naming the
// message.
"use strict";
const fs = require("fs");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { FileHandleReadable } = require("@mcap/nodejs");
const { decompress } = require("fzstd");
const { crc32 } = require("@foxglove/crc");
const protobuf = require("protobufjs");
const descriptor = require("protobufjs/ext/descriptor");

const decompressHandlers = {
  zstd: (buffer, size) => {
    const out = decompress(buffer);
    if (BigInt(out.byteLength) !== size) {
      throw new Error(`zstd chunk gave ${out.byteLength} bytes, not ${size}`);
    }
    return out;
  },
};

const text = new TextDecoder();

// protobufjs types by schema record, built once each.
const protobufTypes = new Map();

// The message as a plain object: JSON parsed, or protobuf decoded with
// every field (defaults too), int64s as numbers, bytes as arrays of numbers
// and row wrappers (NAME_rowK, field "values") as nested arrays, which is
// how the JSON encoding writes the same message.
function decode(channel, schema, message) {
  if (channel.messageEncoding === "protobuf") {
    let type = protobufTypes.get(schema);
    if (type === undefined) {
      const set = descriptor.FileDescriptorSet.decode(schema.data);
      type = protobuf.Root.fromDescriptor(set).lookupType(schema.name);
      protobufTypes.set(schema, type);
    }
    const object = type.toObject(type.decode(message.data), {
      longs: Number, bytes: Array, defaults: true, arrays: true,
    });
    return unwrapRows(type, object);
  }
  try {
    return JSON.parse(text.decode(message.data));
  } catch (e) {
    throw new Error(`${channel.topic}: message ${message.sequence} is not JSON: ${e}`);
  }
}

function isRow(type) {
  return /_row[0-9]+$/.test(type.name) && type.fieldsArray.length === 1 &&
    type.fieldsArray[0].name === "values" && type.parent instanceof protobuf.Type;
}

function unwrapRows(type, object) {
  for (const field of type.fieldsArray) {
    field.resolve();
    const sub = field.resolvedType;
    if (!(sub instanceof protobuf.Type) || object[field.name] == null) continue;
    const one = (v) => {
      const inner = unwrapRows(sub, v);
      return isRow(sub) ? inner.values : inner;
    };
    object[field.name] = field.repeated ? object[field.name].map(one) : one(object[field.name]);
  }
  return object;
}

function check(channels, channel, schema, message) {
  const value = decode(channel, schema, message);
  const required = schema.encoding === "jsonschema"
    ? JSON.parse(text.decode(schema.data)).required || [] : [];
  for (const name of required) {
    if (!(name in value)) {
      throw new Error(`${channel.topic}: message lacks '${name}'`);
    }
  }
  const entry = channels[channel.topic] || (channels[channel.topic] = {
    count: 0, schema: schema.name, schemaEncoding: schema.encoding,
    encoding: channel.messageEncoding, seqs: [],
  });
  entry.count += 1;
  if ("seq" in value) entry.seqs.push(value.seq);
  return value;
}

async function indexed(path, onValue) {
  const handle = await fs.promises.open(path, "r");
  try {
    const reader = await McapIndexedReader.Initialize({
      readable: new FileHandleReadable(handle), decompressHandlers,
    });
    const channels = {};
    for await (const message of reader.readMessages({ validateCrcs: true })) {
      const channel = reader.channelsById.get(message.channelId);
      const value = check(channels, channel, reader.schemasById.get(channel.schemaId), message);
      if (onValue) onValue(channel.topic, value);
    }
    // The indexed reader returns the data section's CRC without checking it.
    const bytes = fs.readFileSync(path);
    const footer = new DataView(bytes.buffer, bytes.byteOffset + bytes.length - 8 - 29);
    const summaryStart = Number(footer.getBigUint64(9, true));
    const dataEnd = summaryStart - 13;
    const crc = crc32(bytes.subarray(0, dataEnd));
    if (reader.dataSectionCrc !== undefined && reader.dataSectionCrc !== crc) {
      throw new Error(`data section CRC ${reader.dataSectionCrc}, computed ${crc}`);
    }
    const s = reader.statistics;
    return {
      channels, complete: true, dataSectionCrc: reader.dataSectionCrc !== undefined,
      chunks: reader.chunkIndexes.length,
      statistics: s && { messageCount: Number(s.messageCount), chunkCount: s.chunkCount,
        channelCount: s.channelCount, schemaCount: s.schemaCount },
    };
  } finally {
    await handle.close();
  }
}

function stream(path) {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(fs.readFileSync(path));
  const schemas = new Map();
  const byId = new Map();
  const channels = {};
  for (let record; (record = reader.nextRecord()) !== undefined;) {
    if (record.type === "Schema") schemas.set(record.id, record);
    else if (record.type === "Channel") byId.set(record.id, record);
    else if (record.type === "Message") {
      const channel = byId.get(record.channelId);
      check(channels, channel, schemas.get(channel.schemaId), record);
    }
  }
  return { channels, complete: reader.done() };
}

// JSON text with every object's keys sorted (protobufjs puts repeated
// fields first).
function canonical(value) {
  if (Array.isArray(value)) return `[${value.map(canonical).join(",")}]`;
  if (value !== null && typeof value === "object") {
    return `{${Object.keys(value).sort().map(
      (k) => `${JSON.stringify(k)}:${canonical(value[k])}`).join(",")}}`;
  }
  return JSON.stringify(value);
}

// Every message of a topic and seq in both files, as JSON text of its
// values: the same run logged in two encodings reads the same.
async function same(a, b) {
  const first = new Map();
  const key = (topic, value) => `${topic}#${value.seq}`;
  await indexed(a, (topic, value) => first.set(key(topic, value), canonical(value)));
  let compared = 0, differ = 0, firstDifference = "";
  await indexed(b, (topic, value) => {
    const other = first.get(key(topic, value));
    if (other === undefined) return;
    compared += 1;
    const mine = canonical(value);
    if (mine !== other) {
      differ += 1;
      if (!firstDifference) firstDifference = `${key(topic, value)}: ${other} vs ${mine}`;
    }
  });
  return { compared, differ, first_difference: firstDifference };
}

async function main() {
  const [mode, path, other] = process.argv.slice(2);
  if (!path || (mode !== "indexed" && mode !== "stream" && mode !== "same") ||
      (mode === "same" && !other)) {
    console.error("usage: node read_mcap.js indexed|stream FILE | same FILE_A FILE_B");
    process.exit(2);
  }
  const result = mode === "indexed" ? await indexed(path)
    : mode === "stream" ? stream(path) : await same(path, other);
  process.stdout.write(JSON.stringify(result) + "\n");
}

main().catch((e) => {
  console.error(`read_mcap: ${e.message || e}`);
  process.exit(1);
});
