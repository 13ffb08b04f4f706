"use strict";
const token = new URLSearchParams(location.search).get("token");
const withToken = u => token ? u + (u.includes("?") ? "&" : "?") + "token=" + encodeURIComponent(token) : u;
const $ = s => document.querySelector(s);
const gf = window.gf = {scene: null, state: null, history: [], depth: null, last_n_sgo: {},
  moves: new Map(), latency: {taken: [], arrived: []}};
const sub = (a, b) => [a[0]-b[0], a[1]-b[1], a[2]-b[2]];
const dot = (a, b) => a[0]*b[0] + a[1]*b[1] + a[2]*b[2];
const cross = (a, b) => [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]];
const norm = a => { const l = Math.hypot(a[0], a[1], a[2]); return [a[0]/l, a[1]/l, a[2]/l]; };
const colour = c => "rgb(" + c.map(v => Math.round(255 * Math.min(1, v))).join(",") + ")";

// The frame's camera, as the renderer builds it (render/scene/camera.cpp: lookAt, perspective).
function basis() {
  const c = gf.scene.camera, f = norm(sub(c.target, c.position)), s = norm(cross(f, c.up));
  return {eye: c.position, f, s, u: cross(s, f), k: 1 / Math.tan(c.fov_deg * Math.PI / 360),
          aspect: gf.scene.width / gf.scene.height};
}
gf.project = p => {
  const b = basis(), d = sub(p, b.eye), z = dot(d, b.f), r = $("#frame").getBoundingClientRect();
  const x = b.k / b.aspect * dot(d, b.s) / z, y = b.k * dot(d, b.u) / z;
  return [r.left + (x + 1) / 2 * r.width, r.top + (1 - y) / 2 * r.height];
};
// The scene point under viewport pixel (px, py) at `depth` metres in front of the camera.
function unproject(px, py, depth) {
  const b = basis(), r = $("#frame").getBoundingClientRect();
  const x = (px - r.left) / r.width * 2 - 1, y = 1 - (py - r.top) / r.height * 2;
  const xs = x * depth * b.aspect / b.k, ys = y * depth / b.k;
  return [0, 1, 2].map(i => b.eye[i] + depth * b.f[i] + xs * b.s[i] + ys * b.u[i]);
}

async function command(line) {
  const posted = performance.now();
  const res = await fetch(withToken("command"), {method: "POST", body: line});
  const text = (await res.text()).trim();
  const move = /^ok .* move (\d+)$/.exec(text);
  if (move && gf.timing) {  // only while this page reads the stream (not a participant's page)
    const n = Number(move[1]), m = {posted};
    if (!match(n, m)) gf.moves.set(n, m);
  }
  const a = $("#answer");
  a.textContent = line + "\n→ " + (text.length > 300 ? text.slice(0, 300) + "…" : text);
  a.className = text.startsWith("ok") ? "" : "err";
  return text;
}

function fingerState(name) { return gf.state && gf.state.fingers.find(f => f.name === name); }

// An element with a class and text (never HTML: names come from scene files).
function element(tag, text, cls) {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  if (cls) e.className = cls;
  return e;
}
function swatch(c) { const d = element("span", undefined, "dot"); d.style.background = colour(c); return d; }

function buildSettings() {
  const box = $("#settings");
  for (const f of gf.scene.fingers) {
    const h = element("div");
    h.append(swatch(f.colour), element("b", f.name), " (" + f.device + ")");
    box.appendChild(h);
    const g = document.createElement("div");
    g.className = "settings";
    for (const w of gf.scene.widgets) {
      const label = document.createElement("label"), input = document.createElement("input");
      label.textContent = w.label;
      input.dataset.finger = f.name;
      input.dataset.field = w.field;
      if (w.field === "god_finger") {
        input.type = "checkbox";
        input.addEventListener("change", () => {
          const n = input.checked ? (gf.last_n_sgo[f.name] || 8) : 0;
          command("set fingers." + f.name + ".n_sgo=" + n);
        });
      } else {
        input.type = "number";
        input.min = w.lo; input.max = w.hi;
        input.step = w.integer ? 1 : (w.hi - w.lo) / 100;
        input.addEventListener("change", () =>
          command("set fingers." + f.name + "." + w.field + "=" + (Number(input.value) / w.shown_per_unit)));
      }
      g.append(label, input);
    }
    box.appendChild(g);
  }
}

function showSettings(f) {
  for (const w of gf.scene.widgets) {
    const input = document.querySelector('input[data-finger="' + f.name + '"][data-field="' + w.field + '"]');
    if (!input || document.activeElement === input) continue;
    if (w.field === "god_finger") { input.checked = f.settings.n_sgo > 0; continue; }
    const v = f.settings[w.key] * w.shown_per_unit;
    input.value = w.integer ? Math.round(v) : Number(v.toPrecision(4));
  }
  if (f.settings.n_sgo > 0) gf.last_n_sgo[f.name] = f.settings.n_sgo;
}

function showFingers(s) {
  const table = $("#fingers");
  for (const f of s.fingers) {
    const desc = gf.scene.fingers.find(d => d.name === f.name);
    let row = table.querySelector('tr[data-finger="' + f.name + '"]');
    if (!row) {
      row = table.insertRow();
      row.dataset.finger = f.name;
      const name = element("td");
      name.append(swatch(desc.colour), f.name);
      const bar = element("div", undefined, "bar"), fill = element("i");
      fill.style.background = colour(desc.colour);
      bar.appendChild(fill);
      const cell = element("td");
      cell.appendChild(bar);
      row.append(name, element("td", "", "model"), element("td", "", "n_sgo"), element("td", "", "radius"),
                 element("td", "", "force"), cell);
    }
    const force = Math.hypot(...f.force_n), r = f.contacts.length ? f.contacts[0].radius_m * 1e3 : 0;
    row.querySelector(".model").textContent = f.model;
    row.querySelector(".n_sgo").textContent = f.n_sgo;
    row.querySelector(".radius").textContent = r.toFixed(1);
    row.querySelector(".force").textContent = force.toFixed(2);
    row.querySelector(".bar i").style.width = Math.min(100, 100 * force / desc.max_force_n) + "%";
    showSettings(f);
  }
}

function showDevices(s) {
  const t = $("#devices");
  t.replaceChildren();
  const live = gf.scene.fingers.filter(f => f.device !== "track");
  for (const f of live) {
    const d = (s.devices || []).find(x => x.finger === f.name), row = t.insertRow();
    const what = f.device === "web" ? "web pointer" : "udp " + (d ? d.address : "");
    const how = f.device === "web" || !d ? "" : d.packets + " packets" + (d.stale ? ", stale" : "") +
      (d.ramping ? ", ramping " + (100 * d.gain).toFixed(0) + "%" : "");
    row.append(element("td", f.name), element("td", what), element("td", how));
  }
  if (!live.length) t.insertRow().append(element("td", "every finger follows its scripted track"));
}

function drawChart() {
  const c = $("#chart"), g = c.getContext("2d"), h = gf.history, w = c.width, ht = c.height;
  g.clearRect(0, 0, w, ht);
  if (h.length < 2) return;
  const t1 = h[h.length - 1].t, t0 = t1 - 10;
  let top = 1;
  for (const p of h) for (const f of p.f) top = Math.max(top, f);
  top = Math.ceil(top);
  g.fillStyle = "#889"; g.font = "11px sans-serif";
  g.fillText(top + " N", 4, 12); g.fillText("t = " + t1.toFixed(1) + " s", w - 70, ht - 4);
  gf.scene.fingers.forEach((f, i) => {
    g.strokeStyle = colour(f.colour); g.lineWidth = 1.5; g.beginPath();
    h.forEach((p, k) => {
      const x = (p.t - t0) / 10 * w, y = ht - 4 - p.f[i] / top * (ht - 20);
      k ? g.lineTo(x, y) : g.moveTo(x, y);
    });
    g.stroke();
  });
}

async function poll() {
  try {
    const s = await (await fetch(withToken("state.json"))).json();
    if (s.fingers) {
      gf.state = s;
      $("#clock").textContent = "t = " + s.t.toFixed(3) + " s";
      const h = gf.history;
      if (h.length && s.t < h[h.length - 1].t) h.length = 0;
      if (!h.length || s.t > h[h.length - 1].t) h.push({t: s.t, f: s.fingers.map(f => Math.hypot(...f.force_n))});
      while (h.length && h[0].t < s.t - 10) h.shift();
      showFingers(s); showDevices(s); drawChart(); showLatency();
      $("#record").classList.toggle("on", !!(s.view && s.view.recording));
      $("#record").textContent = s.view && s.view.recording ? "stop recording (" + s.view.frames_recorded + ")" : "record frames";
    }
    $("#status").textContent = "";
  } catch (e) { $("#status").textContent = "no answer from the session"; }
  setTimeout(poll, 100);
}

// The pointer drives the chosen web finger: pressed, it follows the pointer at its depth. A
// move goes out at most every 30 ms (the device goes straight there in 30 ms); the last one of
// a burst goes out when its 30 ms are up.
let dragging = false, lastSent = 0, pending = null, timer = null, lastTarget = null;
function send(p) {
  const finger = $("#web-finger").value;
  if (!finger) return;
  pending = p;
  lastTarget = {finger, p, at: performance.now()};
  const wait = 30 - (performance.now() - lastSent);
  if (wait > 0) { if (!timer) timer = setTimeout(() => { timer = null; if (pending) send(pending); }, wait); return; }
  lastSent = performance.now();
  command("move " + finger + " " + pending.map(v => v.toFixed(5)).join(" ") + " 0.03");
  pending = null;
}
function fingerDepth() {
  const f = fingerState($("#web-finger").value), b = basis();
  return f ? dot(sub(f.device, b.eye), b.f) : dot(sub(gf.scene.camera.target, b.eye), b.f);
}
function pointerMove(e) {
  if (!dragging || gf.depth === null) return;
  send(unproject(e.clientX, e.clientY, gf.depth));
}
// Nearer (negative) or further along the view, from the last target sent (notches add up).
function nearer(metres) {
  const name = $("#web-finger").value, f = fingerState(name);
  if (!f) return;
  const b = basis();
  const from = lastTarget && lastTarget.finger === name && performance.now() - lastTarget.at < 1000 ? lastTarget.p : f.device;
  gf.depth = dot(sub(from, b.eye), b.f) + metres;
  send(from.map((v, i) => v + metres * b.f[i]));
}

// The stream, read here rather than by the <img> itself, so that the page sees each part's
// headers: X-Moves-Taken and X-Moves-Arrived number the newest move its frame has taken and
// reached (each move's number comes back in the answer to its POST). A move's delay is from
// its POST to the decoded frame that shows it taken (the device set off) and reached (the
// device at its target, after the move's glide): gf.latency, in ms, the last kLatencyKept.
const kLatencyKept = 200;
const ascii = new TextDecoder("ascii");
function find(buf, from, to, seq) {
  for (let i = from; i + seq.length <= Math.min(to, buf.length); i++) {
    let k = 0;
    while (k < seq.length && buf[i + k] === seq[k]) k++;
    if (k === seq.length) return i;
  }
  return -1;
}
// The frames decoded lately (their marks and when), for moves whose answer comes after them.
const shown = [];
function keep(list, ms) { list.push(ms); if (list.length > kLatencyKept) list.shift(); }
// Times move n (posted at `m.posted`) to the first frames at or after its POST that show it.
function match(n, m) {
  for (const f of shown) {
    if (f.at < m.posted) continue;
    if (m.taken === undefined && n <= f.taken) m.taken = f.at;
    if (m.taken !== undefined && n <= f.arrived) {
      keep(gf.latency.taken, m.taken - m.posted);
      keep(gf.latency.arrived, f.at - m.posted);
      return true;
    }
  }
  return performance.now() - m.posted > 10000;  // never shown (the session ended): dropped
}
function noteShown(taken, arrived, at) {
  shown.push({taken, arrived, at});
  if (shown.length > 256) shown.shift();
  for (const [n, m] of gf.moves) if (match(n, m)) gf.moves.delete(n);
}
function showPart(img, bytes, headers) {
  const value = name => { const m = new RegExp("^" + name + ": *(\\d+)", "mi").exec(headers); return m ? Number(m[1]) : 0; };
  const taken = value("X-Moves-Taken"), arrived = value("X-Moves-Arrived"), old = img.src;
  img.src = URL.createObjectURL(new Blob([bytes], {type: "image/jpeg"}));
  if (old.startsWith("blob:")) URL.revokeObjectURL(old);
  img.decode().then(() => noteShown(taken, arrived, performance.now()), () => {});
}
// The box the frame is shown in: the view's, at the frame's aspect, never above its own size.
function frameBox() {
  const v = $("#view"), fw = gf.scene.width, fh = gf.scene.height;
  const s = Math.min(1, v.clientWidth / fw, v.clientHeight / fh);
  return [Math.max(1, Math.floor(fw * s)), Math.max(1, Math.floor(fh * s))];
}
// The stream is asked for at the width the frame is shown at, in device pixels: the server
// shrinks frames for the widest any watcher asks for, so a small page costs less to encode, send
// and decode. When the view's size settles at another width (a resized window, a top bar that
// wraps), the stream is read again at it.
function streamWidth() {
  return Math.min(gf.scene.width, Math.max(16, Math.ceil(frameBox()[0] * (window.devicePixelRatio || 1))));
}
function placeFrame(img) {
  const [w, h] = frameBox();
  img.style.width = w + "px";
  img.style.height = h + "px";
  clearTimeout(gf.restream);
  gf.restream = setTimeout(() => {
    if (gf.stream && gf.stream.width !== streamWidth()) gf.stream.abort.abort();
  }, 250);
}
async function readStream(img) {
  const crlf2 = [13, 10, 13, 10];
  gf.timing = true;
  for (;;) {
    const abort = new AbortController();
    gf.stream = {width: streamWidth(), abort};
    try {
      const res = await fetch(withToken("stream.mjpg?width=" + gf.stream.width), {cache: "no-store", signal: abort.signal});
      if (!res.ok) throw new Error("HTTP " + res.status);
      const reader = res.body.getReader();
      let buf = new Uint8Array(0);
      for (;;) {
        const {value, done} = await reader.read();
        if (done) break;
        const joined = new Uint8Array(buf.length + value.length);
        joined.set(buf); joined.set(value, buf.length);
        buf = joined;
        for (;;) {  // each whole part: "--boundary", headers, a blank line, Content-Length bytes
          const end = find(buf, 0, 2048, crlf2);
          if (end < 0) break;
          const headers = ascii.decode(buf.subarray(0, end));
          const length = /^Content-Length: *(\d+)/mi.exec(headers);
          if (!length) throw new Error("a stream part without Content-Length");
          const start = end + 4, stop = start + Number(length[1]);
          if (buf.length < stop + 2) break;
          showPart(img, buf.slice(start, stop), headers);
          buf = buf.slice(stop + 2);
        }
      }
    } catch (e) {
      if (abort.signal.aborted) continue;  // resized: read again at once, at the new width
      $("#latency").textContent = "stream: " + e.message;
    }
    await new Promise(r => setTimeout(r, 1000));  // the session may be back: read again
  }
}
const median = a => { const s = [...a].sort((x, y) => x - y); return s.length ? s[s.length >> 1] : NaN; };
function showLatency() {
  const l = gf.latency;
  if (!l.taken.length) return;  // nothing timed yet (or the stream's error stays shown)
  $("#latency").textContent = "move → frame " + median(l.taken.slice(-20)).toFixed(0) + " ms, at target " +
    median(l.arrived.slice(-20)).toFixed(0) + " ms (median of the last " + Math.min(20, l.taken.length) + ")";
}

async function start() {
  gf.scene = await (await fetch(withToken("scene.json"))).json();
  if (gf.scene.participant) return participantStart();  // an experiment's participant (participant.js)
  $("#scene").textContent = gf.scene.scene;
  $("#mode").textContent = gf.scene.mode === "live" ? "live: steps on command" : "realtime";
  const img = $("#frame");
  placeFrame(img);
  new ResizeObserver(() => placeFrame(img)).observe($("#view"));
  readStream(img);
  gf.command = command;
  const select = $("#web-finger");
  for (const f of gf.scene.fingers.filter(f => f.device === "web")) select.add(new Option(f.name, f.name));
  if (!select.options.length) select.add(new Option("(no web finger)", ""));
  buildSettings();
  img.addEventListener("pointerdown", e => {
    e.preventDefault(); img.setPointerCapture(e.pointerId); dragging = true;
    gf.depth = fingerDepth(); pointerMove(e);
  });
  img.addEventListener("pointermove", pointerMove);
  const release = () => { dragging = false; };
  img.addEventListener("pointerup", release);
  img.addEventListener("pointercancel", release);
  img.addEventListener("wheel", e => { e.preventDefault(); nearer(e.deltaY > 0 ? 0.005 : -0.005); }, {passive: false});
  document.addEventListener("keydown", e => {
    if (e.target.tagName === "INPUT") return;
    if (e.key === "w" || e.key === "W") nearer(-0.005);
    if (e.key === "s" || e.key === "S") nearer(0.005);
  });
  $("#record").addEventListener("click", () =>
    command(gf.state && gf.state.view && gf.state.view.recording ? "record stop" : "record start"));
  if (gf.scene.mode === "live") {
    $("#live-controls").hidden = false;
    // Run: the next `step` goes out once the last is answered, at most 30 a second.
    let running = false;
    const steps = Math.max(1, Math.round(gf.scene.haptic_rate_hz / 30));
    const tick = async () => {
      if (!running) return;
      const started = performance.now();
      await command("step " + steps);
      setTimeout(tick, Math.max(0, 33 - (performance.now() - started)));
    };
    $("#step").addEventListener("click", () => command("step 1"));
    $("#run").addEventListener("click", () => {
      running = !running;
      $("#run").textContent = running ? "pause" : "run";
      tick();
    });
  }
  poll();
}
start();
