// Connects to mrsim-foxglove with Foxglove's own client library
// (@foxglove/ws-protocol over `ws`) and checks what a Foxglove user relies
// on. Prints one JSON line of what it saw; exits 0 when every check held
// before the deadline, 1 otherwise (saying what was missing).
//
//   node client_check.js watch URL SUBPROTOCOL ROBOT
//     serverInfo; advertised channels whose schemas are JSON Schemas;
//     a SceneUpdate drawing the robot's frames; FrameTransforms whose poses
//     equal the robot's state of the same time (its JSON channel); time
//     that never goes back.
//   node client_check.js count URL SUBPROTOCOL
//     (for bench/foxglove) subscribes to every channel, prints
//     "subscribed" once /mrsim/tf is, and on SIGTERM one JSON line of the
//     frames it got per topic (robot_tf: the robots' transforms, one per
//     state); decodes little more than the frame headers.
//   node client_check.js image URL SUBPROTOCOL ROBOT
//     a camera channel /camera/ROBOT/K advertised as foxglove.RawImage with
//     its JSON Schema, and a picture on it whose base64 data is width x
//     height x 3 bytes.
//   node client_check.js control URL SUBPROTOCOL EXPECT
//     calls /mrsim/pause: EXPECT "refused" (a serviceCallFailure) or "ok"
//     (a response with ok true).
"use strict";
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const WebSocket = require("ws");

const [mode, url, subprotocol, arg] = process.argv.slice(2);
const kDeadlineMs = 60000;
const seen = { mode, subprotocol };

function finish(ok, why) {
  seen.ok = ok;
  if (why) seen.why = why;
  console.log(JSON.stringify(seen));
  process.exit(ok ? 0 : 1);
}
const deadline = setTimeout(
  () => finish(false, "deadline passed: " + JSON.stringify(missing())),
  kDeadlineMs);
deadline.unref();

const ws = new WebSocket(url, [subprotocol]);
const client = new FoxgloveClient({ ws });
const decoder = new TextDecoder();
const channels = new Map();  // id -> channel
const topics = new Map();    // subscription id -> topic
let serverInfo = null;
let matched = 0;
let sceneFrames = 0;
let times = 0;
let lastTime = -1n;
let timeWentBack = false;
let badSchemas = [];
const tfByTime = new Map();
const stateByTime = new Map();

function missing() {
  const m = [];
  if (!serverInfo) m.push("serverInfo");
  if (mode === "watch") {
    if (ws.protocol !== subprotocol) m.push("subprotocol " + ws.protocol);
    if (sceneFrames === 0) m.push("SceneUpdate with the robot's frames");
    if (matched < 3) m.push(`FrameTransforms equal to states (${matched}/3)`);
    if (times < 5) m.push(`time messages (${times}/5)`);
  }
  return m;
}

function check() {
  if (mode !== "watch") return;
  if (timeWentBack) finish(false, "time went back");
  if (badSchemas.length > 0) finish(false, "bad schemas: " + badSchemas);
  if (missing().length === 0) {
    seen.matched = matched;
    seen.times = times;
    seen.channels = [...channels.values()].map((c) => c.topic);
    finish(true);
  }
}

function samePose(t, p) {
  return t.translation.x === p.position[0] && t.translation.y === p.position[1] &&
    t.translation.z === p.position[2] && t.rotation.w === p.orientation[0] &&
    t.rotation.x === p.orientation[1] && t.rotation.y === p.orientation[2] &&
    t.rotation.z === p.orientation[3];
}

function compare(time) {
  const tf = tfByTime.get(time);
  const state = stateByTime.get(time);
  if (!tf || !state) return;
  tfByTime.delete(time);
  stateByTime.delete(time);
  for (let k = 0; k < state.frames.length; ++k) {
    const name = `${arg}/frame_${k}`;
    const t = tf.transforms.find((x) => x.child_frame_id === name);
    if (!t || t.parent_frame_id !== "world" || !samePose(t, state.frames[k])) {
      finish(false, `${name} at ${time}: ${JSON.stringify(t)} is not ` +
        JSON.stringify(state.frames[k]));
    }
  }
  ++matched;
}

client.on("error", (e) => finish(false, "client error: " + e));
client.on("close", (e) => finish(false, "closed: " + (e && e.code)));
client.on("serverInfo", (info) => {
  serverInfo = info;
  seen.serverName = info.name;
  seen.capabilities = info.capabilities;
  seen.protocol = ws.protocol;
});
client.on("status", (s) => {
  if (mode === "watch") finish(false, "status: " + s.message);
});
client.on("advertise", (list) => {
  for (const c of list) {
    channels.set(c.id, c);
    try {
      const schema = JSON.parse(c.schema);
      if (c.schemaEncoding !== "jsonschema" || schema.type !== "object") {
        badSchemas.push(c.topic);
      }
    } catch (e) {
      badSchemas.push(c.topic + ": " + e);
    }
    if (mode === "count") {
      topics.set(client.subscribe(c.id), c.topic);
      if (c.topic === "/mrsim/tf") console.log("subscribed");
      continue;
    }
    if (mode === "image" && c.topic.startsWith(`/camera/${arg}/`)) {
      if (c.schemaName !== "foxglove.RawImage") {
        finish(false, `${c.topic}: schema ${c.schemaName}`);
      }
      seen.camera = { topic: c.topic, schemaName: c.schemaName };
      topics.set(client.subscribe(c.id), c.topic);
    }
    if (mode !== "watch") continue;
    if (c.topic === "/mrsim/scene" || c.topic === "/mrsim/tf" ||
        c.topic === `MRSIM_STATE_${arg}`) {
      topics.set(client.subscribe(c.id), c.topic);
    }
  }
  check();
});
client.on("time", (t) => {
  if (t.timestamp < lastTime) timeWentBack = true;
  lastTime = t.timestamp;
  ++times;
  check();
});
const counts = {};
client.on("message", (m) => {
  const topic = topics.get(m.subscriptionId);
  if (mode === "count") {
    counts[topic] = (counts[topic] || 0) + 1;
    if (topic === "/mrsim/tf") {
      // A robot's transforms, not the scene objects' (one per state).
      const head = new Uint8Array(m.data.buffer, m.data.byteOffset,
        Math.min(m.data.byteLength, 160));
      if (!decoder.decode(head).includes('"scene/')) {
        counts.robot_tf = (counts.robot_tf || 0) + 1;
      }
    }
    return;
  }
  const payload = JSON.parse(decoder.decode(m.data));
  const time = m.timestamp.toString();
  if (mode === "image") {
    const bytes = Buffer.from(payload.data, "base64").length;
    seen.image = { width: payload.width, height: payload.height, bytes,
      frame_id: payload.frame_id, timestamp: payload.timestamp };
    const ok = payload.encoding === "rgb8" && bytes > 0 &&
      payload.step === payload.width * 3 &&
      bytes === payload.width * payload.height * 3;
    finish(ok, ok ? "" : "a picture that disagrees with its size");
  }
  if (topic === "/mrsim/scene") {
    sceneFrames = payload.entities.filter(
      (e) => e.frame_id.startsWith(`${arg}/frame_`) && e.cubes.length === 1).length;
  } else if (topic === "/mrsim/tf") {
    if (payload.transforms.some((t) => t.child_frame_id.startsWith(`${arg}/`))) {
      tfByTime.set(time, payload);
      compare(time);
    }
  } else if (topic === `MRSIM_STATE_${arg}`) {
    stateByTime.set(time, payload);
    compare(time);
  }
  check();
});

if (mode === "control") {
  const kCallId = 17;
  client.on("advertiseServices", (services) => {
    const pause = services.find((s) => s.name === "/mrsim/pause");
    if (!pause) finish(false, "no /mrsim/pause service");
    client.sendServiceCallRequest({
      serviceId: pause.id, callId: kCallId, encoding: "json",
      data: new TextEncoder().encode("{}"),
    });
  });
  client.on("serviceCallFailure", (f) => {
    seen.failure = f.message;
    finish(arg === "refused" && f.callId === kCallId &&
      /refused/.test(f.message), "a failure: " + f.message);
  });
  client.on("serviceCallResponse", (r) => {
    const response = JSON.parse(decoder.decode(r.data));
    seen.response = response;
    finish(arg === "ok" && r.callId === kCallId && response.ok === true,
      "a response: " + JSON.stringify(response));
  });
} else if (mode === "count") {
  clearTimeout(deadline);
  process.on("SIGTERM", () => {
    seen.counts = counts;
    seen.times = times;
    finish(true);
  });
} else if (mode !== "watch" && mode !== "image") {
  finish(false, "unknown mode " + mode);
}
