// mrsim-foxglove's browser page: a small Foxglove WebSocket client
// (foxglove.websocket.v1, JSON messages) that draws the SceneUpdate's
// shapes with three.js, moves them by the FrameTransforms, follows a robot,
// shows sim time and the real-time factor (the sim status channel), plots a
// chosen column of a robot's state, and calls the simulator's services.
// The page sets document.title to "mrsim: live" once it has drawn the
// robots at the pose of a FrameTransforms (tests wait for it).
import * as THREE from "three";
import { OrbitControls } from "./OrbitControls.js";

const $ = (id) => document.getElementById(id);
const kPlotSeconds = 20;       // sim seconds shown in the plot
const kMaxPlotPoints = 4000;   // bounded memory whatever the state rate

// ---- three.js scene (Z up, as mrsim's world) ----
THREE.Object3D.DEFAULT_UP.set(0, 0, 1);
const view = $("view");
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2330);
const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 200);
camera.position.set(1.2, -1.6, 1.0);
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.set(0, 0, 0);
controls.update();
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(3, -2, 5);
scene.add(sun);
// A 0.25 m grid just above the ground shows scale and motion; fog fades it
// out before its lines crowd into moire at the horizon. Each line is made
// of short segments: software renderers (SwiftShader) drop a whole line
// that has an end behind the camera.
function makeGrid(half, spacing, color) {
  const v = [];
  for (let a = -half; a <= half + 1e-9; a += spacing) {
    for (let b = -half; b < half - 1e-9; b += spacing) {
      v.push(a, b, 0, a, b + spacing, 0, b, a, 0, b + spacing, a, 0);
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.Float32BufferAttribute(v, 3));
  return new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color }));
}
const grid = makeGrid(10, 0.25, 0x7d8799);
grid.position.z = 0.002;
scene.add(grid);
scene.fog = new THREE.Fog(0x1d2330, 4, 12);

const frames = new Map();    // frame id -> THREE.Group placed by transforms
const entities = new Map();  // entity id -> THREE.Object3D
let drawnLive = false;

function frameGroup(id) {
  let g = frames.get(id);
  if (!g) {
    g = new THREE.Group();
    g.visible = id === "world";  // shown once a transform placed it
    frames.set(id, g);
    scene.add(g);
  }
  return g;
}

function material(c) {
  const color = new THREE.Color(c?.r ?? 0.7, c?.g ?? 0.7, c?.b ?? 0.7);
  const a = c?.a ?? 1;
  return new THREE.MeshStandardMaterial({ color, roughness: 0.6, metalness: 0.05,
    transparent: a < 1, opacity: a });
}

function place(obj, pose) {
  const p = pose?.position ?? {}, q = pose?.orientation ?? {};
  obj.position.set(p.x ?? 0, p.y ?? 0, p.z ?? 0);
  obj.quaternion.set(q.x ?? 0, q.y ?? 0, q.z ?? 0, q.w ?? 1);
}

const unitBox = new THREE.BoxGeometry(1, 1, 1);
const unitSphere = new THREE.SphereGeometry(0.5, 24, 16);
const unitCylinder = new THREE.CylinderGeometry(0.5, 0.5, 1, 24);
unitCylinder.rotateX(Math.PI / 2);  // Foxglove's cylinders run along z

function shapeMesh(geometry, s) {
  const m = new THREE.Mesh(geometry, material(s.color));
  place(m, s.pose);
  m.scale.set(s.size?.x ?? 1, s.size?.y ?? 1, s.size?.z ?? 1);
  return m;
}

function removeEntity(id) {
  const e = entities.get(id);
  if (!e) return;
  e.parent?.remove(e);
  e.traverse((o) => o.material?.dispose());
  entities.delete(id);
}

function onSceneUpdate(msg) {
  for (const d of msg.deletions ?? []) {
    if (d.type === 1) for (const id of [...entities.keys()]) removeEntity(id);
    else removeEntity(d.id);
  }
  for (const e of msg.entities ?? []) {
    removeEntity(e.id);
    const obj = new THREE.Group();
    for (const s of e.cubes ?? []) obj.add(shapeMesh(unitBox, s));
    for (const s of e.spheres ?? []) obj.add(shapeMesh(unitSphere, s));
    for (const s of e.cylinders ?? []) obj.add(shapeMesh(unitCylinder, s));
    frameGroup(e.frame_id || "world").add(obj);
    entities.set(e.id, obj);
  }
  updateRobots();
}

function onFrameTransforms(msg) {
  for (const t of msg.transforms ?? []) {
    if (t.parent_frame_id !== "world") continue;  // mrsim's are all in world
    const g = frameGroup(t.child_frame_id);
    const p = t.translation, q = t.rotation;
    g.position.set(p.x, p.y, p.z);
    g.quaternion.set(q.x, q.y, q.z, q.w);
    g.visible = true;
  }
}

// Robots are the entities named ROBOT/frame_K.
function robotNames() {
  const names = new Set();
  for (const id of entities.keys()) {
    const m = /^(.*)\/frame_\d+$/.exec(id);
    if (m) names.add(m[1]);
  }
  return [...names].sort();
}

// The centre of the robot's placed frames and the radius around it (m).
function robotExtent(name) {
  const box = new THREE.Box3();
  for (const [id, g] of frames) {
    if (g.visible && id.startsWith(name + "/frame_")) box.expandByPoint(g.position);
  }
  if (box.isEmpty()) return null;
  return { centre: box.getCenter(new THREE.Vector3()),
           radius: box.getSize(new THREE.Vector3()).length() / 2 };
}

const followSelect = $("follow");
let following = "";
function updateRobots() {
  const names = robotNames();
  const have = new Set([...followSelect.options].map((o) => o.value));
  for (const n of names) {
    if (!have.has(n)) followSelect.add(new Option(n, n));
  }
  if (!following && names.length > 0) {
    following = names[0];
    followSelect.value = following;
    snapCamera = true;
  }
}
let snapCamera = false;
followSelect.addEventListener("change", () => {
  following = followSelect.value;
  snapCamera = true;
});

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}
window.addEventListener("resize", resize);
resize();

let pendingLive = false;
function render() {
  requestAnimationFrame(render);
  if (following) {
    const e = robotExtent(following);
    if (e) {
      // The camera keeps its offset from the target: the robot stays in
      // view while the user can still orbit and zoom around it. A robot
      // just chosen is framed: the camera moves to a distance that fits it.
      const delta = e.centre.clone().sub(controls.target);
      if (!snapCamera) delta.multiplyScalar(0.2);
      controls.target.add(delta);
      camera.position.add(delta);
      if (snapCamera) {
        const offset = camera.position.clone().sub(controls.target);
        offset.setLength(Math.min(Math.max(4.5 * e.radius, 0.7), 20));
        camera.position.copy(controls.target).add(offset);
        snapCamera = false;
      }
    }
  }
  controls.update();
  renderer.render(scene, camera);
  if (pendingLive && !drawnLive) {
    drawnLive = true;
    document.title = "mrsim: live";
  }
}
requestAnimationFrame(render);

// ---- the Foxglove WebSocket protocol ----
const channels = new Map();       // channel id -> channel
const subscriptions = new Map();  // subscription id -> handler
const subOfChannel = new Map();   // channel id -> subscription id
const services = new Map();       // name -> id
const pendingCalls = new Map();   // call id -> service name
let nextSubscription = 1, nextCall = 1;
let ws = null;
const decoder = new TextDecoder(), encoder = new TextEncoder();

function subscribe(channel, handler) {
  if (subOfChannel.has(channel.id)) return;
  const id = nextSubscription++;
  subscriptions.set(id, handler);
  subOfChannel.set(channel.id, id);
  ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id, channelId: channel.id }] }));
}
function unsubscribe(channelId) {
  const id = subOfChannel.get(channelId);
  if (id === undefined) return;
  subscriptions.delete(id);
  subOfChannel.delete(channelId);
  ws.send(JSON.stringify({ op: "unsubscribe", subscriptionIds: [id] }));
}

function onAdvertise(list) {
  for (const c of list) {
    channels.set(c.id, c);
    if (c.encoding !== "json") continue;
    if (c.topic === "/mrsim/scene") subscribe(c, onSceneUpdate);
    else if (c.topic === "/mrsim/tf") {
      subscribe(c, (m) => { onFrameTransforms(m); pendingLive = true; });
    } else if (c.schemaName === "mrsim.sim_status_t") subscribe(c, onStatus);
    else if (c.schemaName === "mrsim.robot_state_t") addStateChannel(c);
  }
}

ws = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/${location.search}`,
                   ["foxglove.websocket.v1"]);
ws.binaryType = "arraybuffer";
ws.onopen = () => { $("conn").textContent = "connected"; $("conn").className = "label"; };
ws.onclose = () => {
  $("conn").textContent = "disconnected (reload to reconnect)";
  $("conn").className = "down";
  document.title = "mrsim: disconnected";
};
ws.onmessage = (event) => {
  if (typeof event.data === "string") {
    let m;
    try { m = JSON.parse(event.data); } catch { return; }
    if (m.op === "advertise") onAdvertise(m.channels ?? []);
    else if (m.op === "unadvertise") for (const id of m.channelIds ?? []) channels.delete(id);
    else if (m.op === "advertiseServices") for (const s of m.services ?? []) services.set(s.name, s.id);
    else if (m.op === "serviceCallFailure") {
      const name = pendingCalls.get(m.callId) ?? "call";
      pendingCalls.delete(m.callId);
      const why = String(m.message ?? "refused");
      say(why.startsWith(name) ? why : `${name}: ${why}`, "refused");
    } else if (m.op === "status" && m.level >= 1) say(m.message, "refused");
    return;
  }
  const d = new DataView(event.data);
  if (d.byteLength < 1) return;
  const op = d.getUint8(0);
  if (op === 1 && d.byteLength >= 13) {          // message data
    const handler = subscriptions.get(d.getUint32(1, true));
    if (!handler) return;
    let msg;
    try { msg = JSON.parse(decoder.decode(new Uint8Array(event.data, 13))); } catch { return; }
    handler(msg);
  } else if (op === 2 && d.byteLength >= 9) {    // time
    showSimTime(Number(d.getBigUint64(1, true)) / 1e9);
  } else if (op === 3 && d.byteLength >= 13) {   // service call response
    const callId = d.getUint32(5, true);
    const name = pendingCalls.get(callId) ?? "call";
    pendingCalls.delete(callId);
    const encLen = d.getUint32(9, true);
    let r = {};
    try { r = JSON.parse(decoder.decode(new Uint8Array(event.data, 13 + encLen))); } catch { /* empty */ }
    if (r.ok === false) say(`${name}: ${r.message || "refused by the simulator"}`, "refused");
    else say(`${name}: done`, "ok");
  }
};

// ---- status, time, controls ----
function say(text, kind) {
  const m = $("message");
  m.textContent = text;
  m.className = kind;
}
function showSimTime(s) { $("simtime").textContent = `${s.toFixed(2)} s`; }
function onStatus(s) {
  showSimTime(s.sim_time);
  $("rtf").textContent = Number.isFinite(s.real_time_factor) ? s.real_time_factor.toFixed(2) : "–";
  $("mode").textContent = ["running", "paused", "stopping"][s.mode] ?? "";
}

function callService(name, request) {
  const id = services.get(name);
  if (id === undefined || ws.readyState !== WebSocket.OPEN) {
    say(`${name}: not offered by this server`, "refused");
    return;
  }
  const callId = nextCall++;
  pendingCalls.set(callId, name);
  const enc = encoder.encode("json"), payload = encoder.encode(JSON.stringify(request));
  const buf = new Uint8Array(13 + enc.length + payload.length);
  const v = new DataView(buf.buffer);
  v.setUint8(0, 2);
  v.setUint32(1, id, true);
  v.setUint32(5, callId, true);
  v.setUint32(9, enc.length, true);
  buf.set(enc, 13);
  buf.set(payload, 13 + enc.length);
  ws.send(buf);
  say(`${name}: sent`, "label");
}
$("pause").onclick = () => callService("/mrsim/pause", {});
$("resume").onclick = () => callService("/mrsim/resume", {});
$("step").onclick = () => callService("/mrsim/step", { steps: 1 });

// ---- the plot of one column of a robot's state ----
const stateChannels = new Map();  // robot -> channel
const columnSelect = $("column");
let plotRobot = "";               // whose state is subscribed to and plotted
let plotPath = "";                // its column ("" until its first state)
let listedRobot = "";             // whose columns the list shows
let points = [];                  // [sim time, value]

function addStateChannel(c) {
  const robot = c.topic.replace(/^.*_STATE_/, "");
  stateChannels.set(robot, c);
  if (!plotRobot) {
    plotRobot = robot;
    subscribe(c, (s) => onState(robot, s));
  } else if (listedRobot) {
    columnSelect.add(new Option(`${robot}: …`, `${robot}\n`));
  }
}

// The list: the plotted robot's columns (named once its first state shows
// how many joints and sensors it has), then one entry per other robot.
function listColumns(robot, s) {
  while (columnSelect.options.length > 0) columnSelect.remove(0);
  for (const col of columnsOf(s)) columnSelect.add(new Option(`${robot}: ${col}`, `${robot}\n${col}`));
  for (const other of [...stateChannels.keys()].sort()) {
    if (other !== robot) columnSelect.add(new Option(`${other}: …`, `${other}\n`));
  }
  listedRobot = robot;
}

// The columns worth plotting: scalars, joints, centre of mass, sensors.
function columnsOf(s) {
  const cols = [];
  (s.joints ?? []).forEach((_, k) => {
    for (const f of ["angle", "speed", "torque"]) cols.push(`joints[${k}].${f}`);
  });
  for (const f of ["com", "com_velocity"]) [0, 1, 2].forEach((k) => cols.push(`${f}[${k}]`));
  cols.push("heading");
  (s.sensor_modules ?? []).forEach((m, k) => {
    if (m.has_force) cols.push(`sensor_modules[${k}].force`);
    (m.distance ?? []).forEach((_, j) => cols.push(`sensor_modules[${k}].distance[${j}]`));
  });
  return cols;
}
function valueAt(s, path) {
  let v = s;
  for (const part of path.match(/[^.[\]]+/g)) v = v?.[/^\d+$/.test(part) ? Number(part) : part];
  return typeof v === "number" ? v : NaN;
}

function onState(robot, s) {
  if (robot !== plotRobot) return;
  if (listedRobot !== robot) {
    listColumns(robot, s);
    if (!plotPath) plotPath = columnsOf(s)[0] ?? "heading";
    columnSelect.value = `${robot}\n${plotPath}`;
  }
  const t = s.sim_time, v = valueAt(s, plotPath);
  if (points.length > 0 && t < points[points.length - 1][0]) points = [];  // a reset
  points.push([t, v]);
  while (points.length > kMaxPlotPoints || (points.length > 0 && points[0][0] < t - kPlotSeconds)) points.shift();
  $("value").textContent = Number.isFinite(v) ? v.toFixed(3) : "";
  drawPlot();
}
columnSelect.addEventListener("change", () => {
  const [robot, path] = columnSelect.value.split("\n");
  if (robot !== plotRobot) {
    // Another robot: its state instead (its columns are listed once its
    // first state arrives).
    const old = stateChannels.get(plotRobot);
    if (old) unsubscribe(old.id);
    plotRobot = robot;
    listedRobot = "";
    const c = stateChannels.get(robot);
    if (c) subscribe(c, (s) => onState(robot, s));
  }
  plotPath = path;
  points = [];
  $("value").textContent = "";
  drawPlot();
});

const plot = $("plot");
function drawPlot() {
  const dpr = window.devicePixelRatio || 1;
  const w = plot.clientWidth, h = plot.clientHeight;
  if (plot.width !== Math.round(w * dpr)) { plot.width = Math.round(w * dpr); plot.height = Math.round(h * dpr); }
  const g = plot.getContext("2d");
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.clearRect(0, 0, w, h);
  const left = 58, right = 8, top = 8, bottom = 22;
  g.strokeStyle = "#4a5670";
  g.strokeRect(left, top, w - left - right, h - top - bottom);
  const finite = points.filter((p) => Number.isFinite(p[1]));
  if (finite.length < 2) return;
  let lo = Math.min(...finite.map((p) => p[1])), hi = Math.max(...finite.map((p) => p[1]));
  if (hi - lo < 1e-9) { lo -= 0.5; hi += 0.5; }
  const pad = 0.08 * (hi - lo);
  lo -= pad; hi += pad;
  const t1 = finite[finite.length - 1][0], t0 = Math.max(finite[0][0], t1 - kPlotSeconds);
  plot.dataset.span = (t1 - t0).toFixed(2);  // sim seconds shown
  const x = (t) => left + (w - left - right) * (t1 > t0 ? (t - t0) / (t1 - t0) : 1);
  const y = (v) => top + (h - top - bottom) * (1 - (v - lo) / (hi - lo));
  g.fillStyle = "#9aa6b8";
  g.font = "12px 'DejaVu Sans Mono', monospace";
  g.textAlign = "right";
  g.fillText(hi.toPrecision(3), left - 4, top + 10);
  g.fillText(lo.toPrecision(3), left - 4, h - bottom);
  g.textAlign = "left";
  g.fillText(`${t0.toFixed(1)} s`, left, h - 6);
  g.textAlign = "right";
  g.fillText(`${t1.toFixed(1)} s`, w - right, h - 6);
  g.strokeStyle = "#5cc8ff";  // not a robot colour: tests look for those
  g.lineWidth = 1.6;
  g.beginPath();
  finite.forEach((p, k) => (k === 0 ? g.moveTo(x(p[0]), y(p[1])) : g.lineTo(x(p[0]), y(p[1]))));
  g.stroke();
}
