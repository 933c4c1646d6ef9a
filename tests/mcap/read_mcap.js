// Reads an MCAP file with the format's reference reader (@mcap/core) and
// prints what it found as one line of JSON, for the tests in this folder.
//
//   node read_mcap.js indexed FILE   open through the summary (chunk indexes),
//                                    every chunk CRC-checked, the data
//                                    section's CRC and the summary's too
//   node read_mcap.js stream FILE    read record by record from the start, as
//                                    a reader does with a file whose writer
//                                    died: up to the last whole record
//
// Output: {"channels": {topic: {"count", "schema", "encoding", "seqs"}},
//          "statistics": ..., "complete": bool}. Every message must parse
// as JSON and hold every property its schema requires; otherwise it exits 1
// naming the message.
"use strict";
const fs = require("fs");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { FileHandleReadable } = require("@mcap/nodejs");
const { decompress } = require("fzstd");
const { crc32 } = require("@foxglove/crc");

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

function check(channels, channel, schema, message) {
  let value;
  try {
    value = JSON.parse(text.decode(message.data));
  } catch (e) {
    throw new Error(`${channel.topic}: message ${message.sequence} is not JSON: ${e}`);
  }
  const required = JSON.parse(text.decode(schema.data)).required || [];
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
}

async function indexed(path) {
  const handle = await fs.promises.open(path, "r");
  try {
    const reader = await McapIndexedReader.Initialize({
      readable: new FileHandleReadable(handle), decompressHandlers,
    });
    const channels = {};
    for await (const message of reader.readMessages({ validateCrcs: true })) {
      const channel = reader.channelsById.get(message.channelId);
      check(channels, channel, reader.schemasById.get(channel.schemaId), message);
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

async function main() {
  const [mode, path] = process.argv.slice(2);
  if (!path || (mode !== "indexed" && mode !== "stream")) {
    console.error("usage: node read_mcap.js indexed|stream FILE");
    process.exit(2);
  }
  const result = mode === "indexed" ? await indexed(path) : stream(path);
  process.stdout.write(JSON.stringify(result) + "\n");
}

main().catch((e) => {
  console.error(`read_mcap: ${e.message || e}`);
  process.exit(1);
});
