// SPDX-License-Identifier: GPL-2.0
// The Advee dashboard: reads advee-web's WebSocket (one JSON object per LCM
// message: {"channel", "utime", fields...}) and /scene.json (robot outline,
// sensor positions, room), and draws them. Plain browser JavaScript.
"use strict";

const STATE_NAMES = ["UNKNOWN", "INIT", "STOP", "RUN", "ERROR", "TERMINATE", "PAUSE"];
const PHASE_NAMES = ["DOWN", "STARTING", "RUNNING", "TERMINATING", "TERMINATED"];
const PLOT_WINDOW_S = 60;
const TRAIL_MAX = 3000;
const COLORS = ["#ff7b72", "#79c0ff", "#d2a8ff", "#7ee787", "#ffa657", "#f2cc60"];

const st = {
  scene: {},
  connected: false,
  modules: new Map(),   // name -> {state, pid, seen, phase, restarts, exit}
  odo: null,            // integrated pose {x, y, h}
  odoTrail: [],
  truth: null,          // {x, y, h}
  truthTrail: [],
  srfs: new Map(),      // id -> range (m), negative/null: no echo
  beacons: [],          // [{id, bearing}]
  temps: new Map(),     // label -> [[t, celsius]]
  speeds: {cmd: [], act: [], odo: []},
  paused: null,         // latest of LL_EVENT_STOP.stop and LL_DATA_POWER.paused
  errors: [],
  recent: [],           // newest first: {channel, utime, line}
  bridge: null,
};

const $ = (id) => document.getElementById(id);
const fmt = (v, d) => (v === null || v === undefined || Number.isNaN(v) ? "-" : Number(v).toFixed(d));
const deg = (rad) => (rad * 180) / Math.PI;
const nowS = () => Date.now() / 1000;

function el(tag, attrs, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

// ---- messages -------------------------------------------------------------

function startPose() {
  const s = st.scene.robot && st.scene.robot.start;
  return s ? {x: s.x, y: s.y, h: s.heading_rad} : {x: 0, y: 0, h: 0};
}

// Time series are on the messages' own clock (utime), so that replayed
// history and live data line up; st.latest is the newest time seen.
function pushSample(arr, t, v) {
  if (arr.length && t <= arr[arr.length - 1][0]) {
    // Older than the newest: history arriving after the present. Insert in
    // time order (the arrays hold at most a minute of samples).
    let i = arr.length;
    while (i > 0 && arr[i - 1][0] > t) i--;
    if (i > 0 && arr[i - 1][0] === t) return;
    arr.splice(i, 0, [t, v]);
    return;
  }
  arr.push([t, v]);
  if (!st.latest || t > st.latest) {
    st.latest = t;
    st.latestAt = nowS();
  }
  while (arr.length && arr[0][0] < t - PLOT_WINDOW_S) arr.shift();
}

function trailAdd(trail, x, y) {
  const last = trail[trail.length - 1];
  if (last && Math.hypot(last[0] - x, last[1] - y) < 0.01) return;
  trail.push([x, y]);
  if (trail.length > TRAIL_MAX) trail.shift();
}

function module(name) {
  if (!st.modules.has(name)) st.modules.set(name, {});
  return st.modules.get(name);
}

const handlers = {
  CM_DATA_STATE(m) {
    Object.assign(module(m.module), {state: m.state, pid: m.pid, seen: nowS()});
  },
  CM_DATA_MODULES(m) {
    Object.assign(module(m.target), {phase: m.phase, restarts: m.restarts, exit: m.exit_status});
  },
  CM_DATA_ERROR(m) {
    st.errors.unshift(m);
    st.errors.length = Math.min(st.errors.length, 50);
  },
  LL_DATA_ODO(m) {
    pushSample(st.speeds.odo, m.utime / 1e6, m.speed_mps);
  },
  // The bridge integrates LL_DATA_ODO (so a page opened late agrees).
  WEB_ODO_POSE(m, replay) {
    if (!replay || !st.odo) st.odo = {x: m.x_m, y: m.y_m, h: m.heading_rad};
    trailAdd(st.odoTrail, m.x_m, m.y_m);
  },
  SIM_DATA_POSE(m, replay) {
    if (!replay || !st.truth) st.truth = {x: m.x_m, y: m.y_m, h: m.heading_rad};
    trailAdd(st.truthTrail, m.x_m, m.y_m);
  },
  LL_DATA_SRFS(m) {
    st.srfs.clear();
    (m.srf_id || []).forEach((id, i) => st.srfs.set(id, m.srf_range_m[i]));
  },
  LL_DATA_BEACONS(m) {
    st.beacons = (m.id || []).map((id, i) => ({id, bearing: m.bearing_rad[i]}));
  },
  LL_CMD_MOTION(m) {
    $("cmd-speed").textContent = fmt(m.speed_mps, 2) + " m/s";
    $("cmd-steering").textContent = fmt(deg(m.steering_rad), 1) + "\u00b0";
  },
  LL_DATA_DRIVES(m, replay) {
    const t = m.utime / 1e6;
    pushSample(st.speeds.cmd, t, m.cmd_speed_mps);
    pushSample(st.speeds.act, t, m.speed_mps);
    if (replay) return;
    $("cmd-speed").textContent = fmt(m.cmd_speed_mps, 2) + " m/s";
    $("act-speed").textContent = fmt(m.speed_mps, 2) + " m/s";
    $("cmd-steering").textContent = fmt(deg(m.cmd_steering_rad), 1) + "\u00b0";
    $("act-steering").textContent = fmt(deg(m.steering_rad), 1) + "\u00b0";
    const axes = ["propulsion", "steering"];
    const parts = (m.state || []).map((s, i) =>
      `${axes[m.axis[i]] || "axis " + m.axis[i]} (node ${m.node[i]}): ${s}` +
      (m.fault[i] ? ` FAULT 0x${(m.error_code[i] >>> 0).toString(16)}` : "") +
      (m.axis[i] === 1 ? (m.homed[i] ? ", homed" : ", not homed") : ""));
    if (m.stopped) parts.push(`stopped: ${m.stop_reason || "?"}`);
    $("drives").textContent = parts.join(" \u00b7 ");
  },
  LL_DATA_TEMPERATURE(m, replay) {
    const t = m.utime / 1e6;
    (m.label || []).forEach((label, i) => {
      if (!st.temps.has(label)) st.temps.set(label, []);
      pushSample(st.temps.get(label), t, m.celsius[i]);
      if (replay) return;
      let cell = $("temp-" + label);
      if (!cell) {
        const row = el("tr");
        row.append(el("td", {}, label));
        cell = el("td", {id: "temp-" + label});
        row.append(cell);
        $("temps").append(row);
      }
      cell.textContent = fmt(m.celsius[i], 1) + " \u00b0C";
    });
  },
  LL_DATA_FANS(m) {
    (m.label || []).forEach((label, i) => {
      let cell = $("fan-" + label);
      if (!cell) {
        const row = el("tr");
        row.append(el("td", {}, label));
        cell = el("td", {id: "fan-" + label});
        row.append(cell);
        $("fans").append(row);
      }
      cell.textContent = (m.rpm[i] < 0 ? "-" : m.rpm[i] + " rpm") + (m.fault[i] ? " STALL" : "") +
                         (m.pwm[i] >= 0 ? ` (pwm ${m.pwm[i]})` : "");
    });
    if (m.fan_fail) $("fans").dataset.fail = "1";
  },
  LL_DATA_POWER(m) {
    $("battery-v").textContent = m.battery_v < 0 ? "battery not measured" : fmt(m.battery_v, 1) + " V";
    const box = $("outputs");
    box.replaceChildren();
    (m.on || []).forEach((on, i) => {
      const a = m.current_a[i];
      box.append(el("button", {class: "out" + (on ? " on" : ""), id: "output-" + i, "data-output": i},
                    `out ${i} ${on ? "on" : "off"}${a !== null && a >= 0 ? " " + fmt(a, 2) + " A" : ""}`));
    });
    st.paused = !!m.paused;
  },
  LL_EVENT_STOP(m) {
    st.paused = !!m.stop;
  },
  WEB_BRIDGE(m) {
    st.bridge = m;
  },
  WEB_LEASE(m) {
    control.onLease(m);
  },
  WEB_CONTROL(m) {
    control.onReply(m);
  },
  // The bridge's last minutes, in order, as one frame right after the
  // newest values: they fill the trails and plots, the present stays. The
  // trails are rebuilt so that they end at the present pose.
  WEB_HISTORY(m) {
    const odoNow = st.odoTrail.slice(), truthNow = st.truthTrail.slice();
    st.odoTrail = [];
    st.truthTrail = [];
    for (const x of m.messages || []) dispatch(x, true);
    for (const [x, y] of odoNow) trailAdd(st.odoTrail, x, y);
    for (const [x, y] of truthNow) trailAdd(st.truthTrail, x, y);
  },
};

const RECENT_MAX = 40;
function dispatch(m, replay) {
  if (!replay && m.line) {
    // describe()'s line without its "CHANNEL t=MONOTONIC" head: shown apart.
    st.recent.unshift({channel: m.channel, utime: m.utime, line: m.line.replace(/^\S+ t=\S+ ?/, "")});
    st.recent.length = Math.min(st.recent.length, RECENT_MAX);
  }
  const h = handlers[m.channel];
  if (h) h(m, !!replay);
}

function onMessage(ev) {
  let m;
  try {
    m = JSON.parse(ev.data);
  } catch (e) {
    return;
  }
  dispatch(m);
  scheduleDraw();
}

// ---- connection -----------------------------------------------------------

let socket = null;  // the page's current WebSocket; a replaced one is ignored

function connect() {
  const ws = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/`);
  socket = ws;
  ws.onopen = () => {
    if (ws !== socket) return;
    st.connected = true;
    control.onSocket(ws);
    updateHeader();
  };
  ws.onmessage = (ev) => { if (ws === socket) onMessage(ev); };
  ws.onclose = () => {
    if (ws !== socket) return;
    disconnected();
    setTimeout(connect, 1000);
  };
}

function disconnected() {
  st.connected = false;
  control.onSocket(null);
  updateHeader();
}

// A new session (login, logout): the old socket still speaks for the old
// one, so the page shows itself disconnected at once and opens a new socket
// (with the new cookie) without the retry's wait.
control.onNewSession(() => {
  const old = socket;
  socket = null;
  disconnected();
  if (old) old.close();
  connect();
});

// ---- drawing --------------------------------------------------------------

let drawPending = false;
function scheduleDraw() {
  if (drawPending) return;
  drawPending = true;
  setTimeout(() => {
    drawPending = false;
    drawAll();
  }, 50);
}

function updateHeader() {
  const c = $("conn-status");
  c.className = "pill " + (st.connected ? "ok" : "bad");
  c.textContent = st.connected ? "connected" : "disconnected, retrying";
  const p = $("pause-indicator");
  if (st.paused === null) {
    p.className = "pill unknown";
    p.textContent = "PAUSE ?";
  } else {
    p.className = "pill " + (st.paused ? "paused" : "ok");
    p.textContent = st.paused ? "PAUSE" : "not paused";
  }
  if (st.bridge)
    $("bridge-stats").textContent =
      `bridge: ${st.bridge.messages} messages, ${st.bridge.clients} client(s), ${st.bridge.dropped} dropped for this page`;
}

function drawModules() {
  const body = $("modules").querySelector("tbody");
  const names = [...st.modules.keys()].sort();
  body.replaceChildren();
  const sel = $("state-target");
  const want = ["*", ...names];
  if ([...sel.options].map((o) => o.value).join() !== want.join()) {
    const keep = sel.value;
    sel.replaceChildren(...want.map((n) => el("option", {value: n}, n === "*" ? "every module (*)" : n)));
    sel.value = want.includes(keep) ? keep : "*";
  }
  const t = nowS();
  for (const name of names) {
    const m = st.modules.get(name);
    const stateName = m.state === undefined ? "-" : STATE_NAMES[m.state] || String(m.state);
    const stale = m.seen !== undefined && t - m.seen > 3;
    const row = el("tr", {id: "module-" + name, class: stale ? "stale" : ""});
    row.append(el("td", {}, name));
    row.append(el("td", {class: "state " + stateName}, stateName));
    row.append(el("td", {}, (m.phase === undefined ? "" : PHASE_NAMES[m.phase] || m.phase) +
                            (m.pid ? ` pid ${m.pid}` : "")));
    row.append(el("td", {}, m.restarts === undefined ? "" : String(m.restarts)));
    row.append(el("td", {}, m.seen === undefined ? "" : fmt(t - m.seen, 0) + " s ago"));
    body.append(row);
  }
}

function drawErrors() {
  const ul = $("errors");
  ul.replaceChildren();
  if (!st.errors.length) ul.append(el("li", {class: "none"}, "none"));
  const min = Number($("error-filter").value);
  const shown = st.errors.filter((e) => e.severity >= min);
  if (st.errors.length && !shown.length) ul.append(el("li", {class: "none"}, "none at this severity"));
  for (const e of shown.slice(0, 12)) {
    const when = new Date(e.utime / 1000).toLocaleTimeString();
    ul.append(el("li", {class: "sev" + e.severity},
                 `${when} ${e.module}: ${e.text}${e.number ? " (" + e.number + ")" : ""}${e.fatal ? " FATAL" : ""}`));
  }
}

function drawRecent() {
  const ul = $("recent");
  ul.replaceChildren();
  for (const r of st.recent) {
    const when = new Date(r.utime / 1000).toLocaleTimeString();
    const li = el("li", {}, "");
    li.append(el("span", {class: "ch"}, r.channel), el("span", {class: "when"}, when), el("span", {}, r.line));
    ul.append(li);
  }
}

// World -> canvas transform fitted to the room (or around the robot).
function view(canvas) {
  let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
  const add = (x, y) => {
    minX = Math.min(minX, x); maxX = Math.max(maxX, x);
    minY = Math.min(minY, y); maxY = Math.max(maxY, y);
  };
  const w = st.scene.world;
  if (w && w.segments.length) {
    for (const s of w.segments) { add(s[0], s[1]); add(s[2], s[3]); }
  } else {
    const c = st.truth || st.odo || startPose();
    add(c.x - 4, c.y - 3); add(c.x + 4, c.y + 3);
  }
  for (const p of st.odoTrail) add(p[0], p[1]);
  const margin = 0.4;
  minX -= margin; minY -= margin; maxX += margin; maxY += margin;
  const scale = Math.min(canvas.width / (maxX - minX), canvas.height / (maxY - minY));
  const ox = (canvas.width - scale * (maxX - minX)) / 2, oy = (canvas.height - scale * (maxY - minY)) / 2;
  return {
    scale,
    px: (x) => ox + (x - minX) * scale,
    py: (y) => canvas.height - (oy + (y - minY) * scale),  // y north = up
    minX, minY, maxX, maxY,
  };
}

function toWorld(pose, x, y) {
  const c = Math.cos(pose.h), s = Math.sin(pose.h);
  return [pose.x + c * x - s * y, pose.y + s * x + c * y];
}

function drawRobot(ctx, v, pose, color, fill) {
  const o = (st.scene.robot && st.scene.robot.outline) || {front_m: 0.9, rear_m: 0.25, half_width_m: 0.3};
  const pts = [[o.front_m, o.half_width_m], [-o.rear_m, o.half_width_m], [-o.rear_m, -o.half_width_m],
               [o.front_m, -o.half_width_m]].map(([x, y]) => toWorld(pose, x, y));
  ctx.beginPath();
  pts.forEach(([x, y], i) => (i ? ctx.lineTo(v.px(x), v.py(y)) : ctx.moveTo(v.px(x), v.py(y))));
  ctx.closePath();
  ctx.fillStyle = fill;
  ctx.fill();
  ctx.strokeStyle = color;
  ctx.lineWidth = 2;
  ctx.stroke();
  // Heading arrow from the rear axle.
  const tip = toWorld(pose, o.front_m * 0.8, 0);
  ctx.beginPath();
  ctx.moveTo(v.px(pose.x), v.py(pose.y));
  ctx.lineTo(v.px(tip[0]), v.py(tip[1]));
  ctx.stroke();
}

function drawTrail(ctx, v, trail, color) {
  if (trail.length < 2) return;
  ctx.beginPath();
  trail.forEach(([x, y], i) => (i ? ctx.lineTo(v.px(x), v.py(y)) : ctx.moveTo(v.px(x), v.py(y))));
  ctx.strokeStyle = color;
  ctx.lineWidth = 1.5;
  ctx.setLineDash([4, 3]);
  ctx.stroke();
  ctx.setLineDash([]);
}

function drawMap() {
  const canvas = $("map");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const v = view(canvas);
  const css = getComputedStyle(document.documentElement);
  const color = (name) => css.getPropertyValue(name).trim();

  // 1 m grid
  ctx.strokeStyle = "#18212b";
  ctx.lineWidth = 1;
  for (let x = Math.ceil(v.minX); x <= v.maxX; x++) {
    ctx.beginPath(); ctx.moveTo(v.px(x), 0); ctx.lineTo(v.px(x), canvas.height); ctx.stroke();
  }
  for (let y = Math.ceil(v.minY); y <= v.maxY; y++) {
    ctx.beginPath(); ctx.moveTo(0, v.py(y)); ctx.lineTo(canvas.width, v.py(y)); ctx.stroke();
  }
  ctx.fillStyle = "#56626e";
  ctx.font = "11px DejaVu Sans, sans-serif";
  ctx.fillText("1 m grid, x east, y north", 8, canvas.height - 8);

  const w = st.scene.world;
  if (w) {
    ctx.strokeStyle = "#c9d1d9";
    ctx.lineWidth = 3;
    for (const s of w.segments) {
      ctx.beginPath(); ctx.moveTo(v.px(s[0]), v.py(s[1])); ctx.lineTo(v.px(s[2]), v.py(s[3])); ctx.stroke();
    }
    for (const c of w.circles) {
      ctx.beginPath(); ctx.arc(v.px(c[0]), v.py(c[1]), c[2] * v.scale, 0, 2 * Math.PI); ctx.stroke();
    }
    for (const b of w.beacons) {
      ctx.fillStyle = color("--bearing");
      ctx.beginPath(); ctx.arc(v.px(b.x), v.py(b.y), 6, 0, 2 * Math.PI); ctx.fill();
      ctx.fillStyle = "#fff";
      ctx.font = "bold 11px DejaVu Sans, sans-serif";
      ctx.fillText("B" + b.id, v.px(b.x) + 8, v.py(b.y) - 8);
    }
  }

  drawTrail(ctx, v, st.truthTrail, color("--truth"));
  drawTrail(ctx, v, st.odoTrail, color("--odo"));

  // Sensors are drawn from the true pose when there is one: there the rays
  // meet the walls they measured; else from the robot's own estimate.
  const sensePose = st.truth || st.odo;
  const robot = st.scene.robot;
  if (sensePose && robot) {
    const maxR = robot.srf_max_m || 6;
    for (const s of robot.srfs) {
      const r = st.srfs.get(s.id);
      if (r === undefined) continue;
      const [sx, sy] = toWorld(sensePose, s.x, s.y);
      const echo = r !== null && r >= 0;
      const len = echo ? r : Math.min(maxR, 0.5);
      const a = sensePose.h + s.heading_rad;
      ctx.strokeStyle = echo ? color("--ray") : "#5a3434";
      ctx.lineWidth = echo ? 1.5 : 1;
      if (!echo) ctx.setLineDash([2, 3]);
      ctx.beginPath();
      ctx.moveTo(v.px(sx), v.py(sy));
      ctx.lineTo(v.px(sx + len * Math.cos(a)), v.py(sy + len * Math.sin(a)));
      ctx.stroke();
      ctx.setLineDash([]);
      if (echo) {
        ctx.fillStyle = color("--ray");
        ctx.beginPath(); ctx.arc(v.px(sx + r * Math.cos(a)), v.py(sy + r * Math.sin(a)), 2.5, 0, 2 * Math.PI); ctx.fill();
      }
    }
    const sc = robot.scanner || {x: 0, y: 0};
    const [bx, by] = toWorld(sensePose, sc.x, sc.y);
    ctx.strokeStyle = color("--bearing");
    ctx.lineWidth = 1;
    for (const b of st.beacons) {
      const a = sensePose.h + b.bearing;
      const known = w && w.beacons.find((x) => x.id === b.id);
      const len = known ? Math.hypot(known.x - bx, known.y - by) : 3;
      ctx.setLineDash([6, 4]);
      ctx.beginPath();
      ctx.moveTo(v.px(bx), v.py(by));
      ctx.lineTo(v.px(bx + len * Math.cos(a)), v.py(by + len * Math.sin(a)));
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }
  if (st.truth) drawRobot(ctx, v, st.truth, color("--truth"), "rgba(227,179,65,0.12)");
  if (st.odo) drawRobot(ctx, v, st.odo, color("--odo"), "rgba(88,166,255,0.18)");
  if (!st.odo && !st.truth) {
    ctx.fillStyle = "#8696a7";
    ctx.font = "14px DejaVu Sans, sans-serif";
    ctx.fillText("waiting for LL_DATA_ODO / SIM_DATA_POSE", 20, 30);
  }

  const poseText = (p) => (p ? `x ${fmt(p.x, 2)} m  y ${fmt(p.y, 2)} m  heading ${fmt(deg(p.h), 1)}\u00b0` : "-");
  $("odo-pose").textContent = poseText(st.odo);
  $("true-pose").textContent = poseText(st.truth);
  $("pose-error").textContent = st.odo && st.truth ? fmt(Math.hypot(st.odo.x - st.truth.x, st.odo.y - st.truth.y), 3) + " m" : "-";
}

// Time plot of named series [[t, v]] over the last PLOT_WINDOW_S seconds.
function drawPlot(canvas, series) {
  // Match the drawing buffer to the laid-out size so text stays crisp.
  const r = canvas.getBoundingClientRect();
  if (r.width && canvas.width !== Math.round(r.width)) canvas.width = Math.round(r.width);
  const ctx = canvas.getContext("2d");
  const W = canvas.width, H = canvas.height, L = 44, R = 8, T = 8, B = 18;
  ctx.clearRect(0, 0, W, H);
  // The axis ends at the newest message's time, moved on by the local
  // clock since it came (the robot's and the browser's clocks may differ).
  const t1 = st.latest ? st.latest + (nowS() - st.latestAt) : nowS(), t0 = t1 - PLOT_WINDOW_S;
  let lo = Infinity, hi = -Infinity;
  for (const s of series) for (const [, y] of s.data) if (y !== null) { lo = Math.min(lo, y); hi = Math.max(hi, y); }
  if (lo === Infinity) { lo = 0; hi = 1; }
  if (hi - lo < 1e-6) { lo -= 0.5; hi += 0.5; }
  const pad = (hi - lo) * 0.1;
  lo -= pad; hi += pad;
  const X = (t) => L + ((t - t0) / PLOT_WINDOW_S) * (W - L - R);
  const Y = (y) => T + (1 - (y - lo) / (hi - lo)) * (H - T - B);
  ctx.font = "10px DejaVu Sans, sans-serif";
  ctx.fillStyle = "#8696a7";
  ctx.strokeStyle = "#1f2934";
  for (let i = 0; i <= 4; i++) {
    const y = lo + ((hi - lo) * i) / 4;
    ctx.beginPath(); ctx.moveTo(L, Y(y)); ctx.lineTo(W - R, Y(y)); ctx.stroke();
    ctx.fillText(fmt(y, Math.abs(hi - lo) < 5 ? 2 : 1), 2, Y(y) + 3);
  }
  for (let s = 0; s <= PLOT_WINDOW_S; s += 10) ctx.fillText(`-${PLOT_WINDOW_S - s}s`, X(t0 + s) - 10, H - 4);
  series.forEach((s, k) => {
    ctx.strokeStyle = s.color || COLORS[k % COLORS.length];
    ctx.lineWidth = s.width || 2;
    ctx.setLineDash(s.dash || []);
    ctx.beginPath();
    let started = false;
    for (const [t, y] of s.data) {
      if (y === null) continue;
      started ? ctx.lineTo(X(t), Y(y)) : ctx.moveTo(X(t), Y(y));
      started = true;
    }
    ctx.stroke();
    ctx.setLineDash([]);
    if (s.label && s.data.length) {
      const last = s.data[s.data.length - 1];
      ctx.fillStyle = ctx.strokeStyle;
      ctx.fillText(s.label, Math.min(X(last[0]) - 40, W - 60), Y(last[1]) - 4);
    }
  });
}

function drawAll() {
  updateHeader();
  drawModules();
  drawErrors();
  drawRecent();
  drawMap();
  drawPlot($("plot-temp"), [...st.temps.entries()].map(([label, data]) => ({label, data})));
  drawPlot($("plot-speed"), [
    // Wide to narrow: equal curves stay visible on top of each other.
    {data: st.speeds.cmd, color: "#f0883e", width: 6},
    {data: st.speeds.act, color: "#3fb950", width: 3},
    {data: st.speeds.odo, color: "#58a6ff", width: 1.5, dash: [5, 3]},
  ]);
}

fetch("scene.json")
  .then((r) => r.json())
  .then((scene) => {
    st.scene = scene;
    scheduleDraw();
  })
  .catch(() => {})
  .finally(connect);
$("error-filter").addEventListener("change", drawErrors);
setInterval(drawAll, 1000);  // ages and the moving time axis
drawAll();
