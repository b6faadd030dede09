// SPDX-License-Identifier: GPL-2.0
// The dashboard's controls: login, the control lease, driving with the
// joystick and the arrow keys under the dead-man rule, module states, power,
// homing. Every request goes over the page's WebSocket to advee-web, which
// checks the session and the lease again (docs/web-dashboard.md "Control").
// Loaded before dashboard.js, which calls control.onLease/onReply/onSocket
// and gives control.onNewSession the page's reconnect.
"use strict";

const control = (() => {
  const DRIVE_EVERY_MS = 100;  // repeat while held: driver_canbus stops after 1 s without
  const c = {
    ws: null,
    user: null,          // logged-in operator of this page, null = none
    holder: null,        // who holds the lease
    mine: false,         // this page holds it
    limits: {max_speed_mps: 0.5, max_steering_rad: 0.5},
    stick: null,         // joystick deflection {x, y} in -1..1 while held
    keys: new Set(),     // arrow keys held
    timer: null,
    last: null,          // last drive request sent
    newSession: null,    // dashboard.js: replace the socket after login/logout
  };
  const $ = (id) => document.getElementById(id);

  function send(obj) {
    if (!c.ws || c.ws.readyState !== WebSocket.OPEN) return false;
    c.ws.send(JSON.stringify(obj));
    return true;
  }

  function status(text, bad) {
    const s = $("control-msg");
    s.textContent = text;
    s.className = "small " + (bad ? "bad" : "");
  }

  // ---- driving: commands flow only while a control is held ----------------
  function demand() {
    if (c.stick) return {speed: -c.stick.y, steer: -c.stick.x};
    let speed = 0, steer = 0;
    if (c.keys.has("ArrowUp")) speed += 1;
    if (c.keys.has("ArrowDown")) speed -= 1;
    if (c.keys.has("ArrowLeft")) steer += 1;
    if (c.keys.has("ArrowRight")) steer -= 1;
    return c.keys.size ? {speed, steer} : null;
  }

  function driveNow() {
    const d = demand();
    if (!d || !c.mine) return stop();
    // Three decimals, towards zero: never beyond the limit the bridge checks.
    const r = (v, m) => Math.trunc(Math.max(-1, Math.min(1, v)) * m * 1000) / 1000;
    const req = {type: "drive", speed_mps: r(d.speed, c.limits.max_speed_mps),
                 steering_rad: r(d.steer, c.limits.max_steering_rad)};
    send(req);
    c.last = req;
    $("drive-cmd").textContent = `${req.speed_mps.toFixed(2)} m/s, ${(req.steering_rad * 180 / Math.PI).toFixed(1)}°`;
    if (!c.timer) c.timer = setInterval(driveNow, DRIVE_EVERY_MS);
  }

  // The dead-man rule: release, blur, hidden page, closing: stop at once.
  // `tell` false: the bridge has stopped the robot already (lease lost).
  function stop(tell = true) {
    c.stick = null;
    c.keys.clear();
    if (c.timer) clearInterval(c.timer);
    c.timer = null;
    drawStick();
    if (tell && (c.last || c.mine)) send({type: "stop"});
    c.last = null;
    $("drive-cmd").textContent = "stopped";
  }

  // ---- joystick (pointer events: mouse, touch, pen) ------------------------
  function drawStick() {
    const cv = $("joystick");
    const ctx = cv.getContext("2d");
    const W = cv.width, R = W / 2 - 8;
    ctx.clearRect(0, 0, W, W);
    ctx.strokeStyle = "#2b3642";
    ctx.lineWidth = 2;
    ctx.beginPath(); ctx.arc(W / 2, W / 2, R, 0, 2 * Math.PI); ctx.stroke();
    ctx.beginPath(); ctx.moveTo(W / 2, 8); ctx.lineTo(W / 2, W - 8); ctx.moveTo(8, W / 2); ctx.lineTo(W - 8, W / 2); ctx.stroke();
    const s = c.stick || {x: 0, y: 0};
    ctx.fillStyle = c.mine ? (c.stick ? "#58a6ff" : "#3b4b5c") : "#262d35";
    ctx.beginPath(); ctx.arc(W / 2 + s.x * R, W / 2 + s.y * R, 26, 0, 2 * Math.PI); ctx.fill();
  }

  function stickAt(ev) {
    const cv = $("joystick");
    const b = cv.getBoundingClientRect();
    let x = ((ev.clientX - b.left) / b.width) * 2 - 1, y = ((ev.clientY - b.top) / b.height) * 2 - 1;
    const n = Math.hypot(x, y);
    if (n > 1) { x /= n; y /= n; }
    c.stick = {x, y};
    drawStick();
  }

  function setupJoystick() {
    const cv = $("joystick");
    cv.addEventListener("pointerdown", (ev) => {
      if (!c.mine) return status("take control first", true);
      ev.preventDefault();
      cv.setPointerCapture(ev.pointerId);
      stickAt(ev);
      driveNow();
    });
    cv.addEventListener("pointermove", (ev) => { if (c.stick) stickAt(ev); });
    for (const t of ["pointerup", "pointercancel", "lostpointercapture"])
      cv.addEventListener(t, () => { if (c.stick) stop(); });
    drawStick();
  }

  function setupKeys() {
    const arrows = ["ArrowUp", "ArrowDown", "ArrowLeft", "ArrowRight"];
    window.addEventListener("keydown", (ev) => {
      if (!arrows.includes(ev.key) || ev.target.tagName === "INPUT" || ev.target.tagName === "SELECT") return;
      ev.preventDefault();
      if (!c.mine || ev.repeat) return;
      c.keys.add(ev.key);
      driveNow();
    });
    window.addEventListener("keyup", (ev) => {
      if (!c.keys.delete(ev.key)) return;
      if (c.keys.size) driveNow(); else stop();
    });
    window.addEventListener("blur", () => { if (c.timer) stop(); });
    document.addEventListener("visibilitychange", () => { if (document.hidden && c.timer) stop(); });
    window.addEventListener("pagehide", () => { if (c.timer) stop(); });
  }

  // ---- login --------------------------------------------------------------
  async function post(path, body) {
    const r = await fetch(path, {method: "POST", headers: {"Content-Type": "application/json"},
                                 body: JSON.stringify(body || {}), credentials: "same-origin"});
    let j = {};
    try { j = await r.json(); } catch (e) { /* empty */ }
    return {ok: r.ok, j};
  }

  async function refreshSession() {
    try {
      const r = await fetch("session", {credentials: "same-origin"});
      const j = await r.json();
      c.user = j.user;
      c.limits = {max_speed_mps: j.max_speed_mps, max_steering_rad: j.max_steering_rad};
    } catch (e) { /* the bridge is away: the socket's retry shows it */ }
    render();
  }

  function setupLogin() {
    $("login-form").addEventListener("submit", async (ev) => {
      ev.preventDefault();
      const {ok, j} = await post("login", {user: $("login-user").value, password: $("login-password").value});
      $("login-password").value = "";
      if (!ok) return status(j.error || "login failed", true);
      status("logged in as " + j.user);
      if (c.newSession) c.newSession();  // the new socket carries the session cookie
      await refreshSession();
    });
    $("logout").addEventListener("click", async () => {
      stop();
      await post("logout");
      if (c.newSession) c.newSession();
      await refreshSession();
      status("logged out");
    });
  }

  // ---- buttons ------------------------------------------------------------
  function setupButtons() {
    $("take").addEventListener("click", () => {
      if (c.holder && !c.mine && !confirm(`${c.holder} holds control. Take it over?`)) return;
      send({type: "take", force: !!c.holder});
    });
    $("release").addEventListener("click", () => { stop(); send({type: "release"}); });
    $("stop").addEventListener("click", () => stop());
    $("stop").addEventListener("pointerdown", () => stop());  // a touch stops before the click comes
    for (const b of document.querySelectorAll("[data-state]"))
      b.addEventListener("click", () => {
        const target = $("state-target").value, state = b.dataset.state;
        if (!target) return status("choose a module", true);
        if (confirm(`Set ${target === "*" ? "every module" : target} to ${state}?`))
          send({type: "state", target, state, confirmed: true});
      });
    $("homing").addEventListener("click", () => send({type: "homing", axis: "steering"}));
    for (const [id, action, what] of [["poweroff", "poweroff", "Power off the computer"],
                                      ["reboot", "reboot", "Reboot the computer"]])
      $(id).addEventListener("click", () => {
        if (confirm(what + "?")) send({type: "power", action, confirmed: true});
      });
    $("outputs").addEventListener("click", (ev) => {
      const o = ev.target.closest("[data-output]");
      if (!o || !c.mine) return;
      const n = Number(o.dataset.output), on = !o.classList.contains("on");
      if (confirm(`Switch power output ${n} ${on ? "on" : "off"}?`))
        send({type: "power", action: "output", output: n, on, confirmed: true});
    });
  }

  function render() {
    $("login-form").hidden = !!c.user;
    $("logout").hidden = !c.user;
    $("operator").textContent = c.user ? c.user : "not logged in";
    $("lease").textContent = c.mine ? "you have control" : c.holder ? `control: ${c.holder}` : "control: free";
    $("lease").className = "pill " + (c.mine ? "ok" : c.holder ? "paused-soft" : "unknown");
    $("take").hidden = !c.user || c.mine;
    $("take").textContent = c.holder && !c.mine ? "Take over control" : "Take control";
    $("release").hidden = !c.mine;
    document.body.classList.toggle("in-control", c.mine);
    $("limits").textContent = `limits ${c.limits.max_speed_mps.toFixed(2)} m/s, ` +
      `${(c.limits.max_steering_rad * 180 / Math.PI).toFixed(0)}° steering`;
    drawStick();
  }

  setupJoystick();
  setupKeys();
  setupLogin();
  setupButtons();
  refreshSession();

  return {
    onNewSession(reconnect) { c.newSession = reconnect; },
    onSocket(ws) {
      if (!ws) { c.mine = false; c.holder = null; stop(false); }
      c.ws = ws;
      render();
    },
    onLease(m) {
      const wasMine = c.mine;
      c.holder = m.holder;
      c.mine = m.you;
      if (wasMine && !c.mine) {
        stop(false);
        status(m.event === "taken" && m.by ? `${m.by} took control over` : "control released", m.event === "taken");
        // Refusals of commands that were on their way must not hide it.
        c.keepStatusUntil = Date.now() + 5000;
      }
      render();
    },
    onReply(m) {
      if (!m.ok && !c.mine && Date.now() < (c.keepStatusUntil || 0)) return;
      status(m.ok ? "done: " + m.request : "refused: " + m.error, !m.ok);
    },
  };
})();
