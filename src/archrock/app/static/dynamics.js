// archrock app: the page's dynamics (a pulse or a record, the model that answers it, the
// animation and the time history). Loaded before app.js, whose helpers it calls ($, el, post, ...).
"use strict";
// ------------------------------------------------------------------ dynamics
function pulseParams() {
  return {kind: $("pulse-kind").value, amplitude: $("amplitude").value.trim(),
          duration: $("duration").value.trim()};
}

// the ground motion of a response: {pulse} or, when chosen and loaded, {record: {id}}
function motionParams() {
  if ($("motion").value === "record") {
    if (!app.record) {
      showError("record: open a record file (PEER .AT2 or two columns 'time accel') or choose a suite's record first");
      const err = new Error("no record");
      err.handled = true;
      throw err;
    }
    return {record: {id: app.record.id}};
  }
  return {pulse: pulseParams()};
}

// send a file's bytes (a record or a DXF survey) to the server, which reads it with the library
async function upload(url, file, params) {
  if (file.size > MAX_FILE_BYTES) {
    showError(`${file.name}: ${file.size} bytes; the app reads files of up to 20 MB`);
    return null;
  }
  const q = new URLSearchParams({name: file.name, ...params});
  let resp;
  try {
    resp = await api(`${url}?${q}`, {method: "POST", body: file,
                                       headers: {"Content-Type": "application/octet-stream"}});
  } catch (e) {
    showError("the archrock server does not answer (is `archrock app` still running?)");
    return null;
  }
  const data = await resp.json().catch(() => ({error: `HTTP ${resp.status}`}));
  const control = url === "/api/dxf" ? "upload-dxf" : "record-file";
  if (!resp.ok) {
    showError(data.error || `HTTP ${resp.status}`);
    showRefusal(control, `refused: ${data.error || `HTTP ${resp.status}`}`);
    return null;
  }
  clearError();
  clearRefusals([control]);
  return data;
}

async function loadRecord() {
  const file = $("record-file").files[0];
  if (!file) return;
  const t0 = performance.now();
  const r = await upload("/api/record", file, {units: $("record-units").value,
                                               scale: $("record-scale").value.trim()});
  if (!r) return;
  app.recordSource = "file";
  await showRecord(r, t0);
}

// units or scale changed: the record chosen last (a file or a suite's) is read again
function reloadRecord() {
  return app.recordSource === "suite" ? loadSuiteRecord() : loadRecord();
}

// ------------------------------------------------------------------ the built-in suites
// the FEMA P695 sets (extra "records"): the menu lists them; a record chosen is read by the
// server as an uploaded file is, and its id then stands for it (play)
function option(value, text) {
  const o = document.createElement("option");
  o.value = value;
  o.textContent = text;
  return o;
}

async function loadSuites() {
  let d;
  try {
    d = await (await api("/api/suites")).json();
  } catch (e) {
    return;  // the server is gone: the next request says so
  }
  for (const s of d.suites || []) {
    const o = option(s.name, s.name);
    o.title = s.description;
    $("record-suite").appendChild(o);
  }
  if (!d.installed) {
    $("record-suite").disabled = $("suite-record").disabled = true;
    $("suite-info").textContent = d.install;
  }
}

async function listSuite() {
  const name = $("record-suite").value, menu = $("suite-record");
  menu.replaceChildren(option("", "a record ..."));
  if (!name) return;
  const resp = await api(`/api/suites/${encodeURIComponent(name)}`);
  const d = await resp.json().catch(() => ({error: `HTTP ${resp.status}`}));
  if (!resp.ok) {
    showError(d.error || `HTTP ${resp.status}`);
    showRefusal("record-suite", `refused: ${d.error || `HTTP ${resp.status}`}`);
    return;
  }
  clearRefusals(["record-suite"]);
  for (const r of d.records) {
    menu.appendChild(option(r.ref, `${r.record}${r.component} ${r.event} ${r.year}, ` +
        `${r.station}: PGA ${fmt(r.pga_g)} g, ${fmt(r.duration, 1)} s`));
  }
  $("suite-info").textContent = `${d.count} records of ${name}`;
}

async function loadSuiteRecord() {
  const ref = $("suite-record").value;
  if (!ref) return;
  const t0 = performance.now();
  let r;
  try {
    r = await post("/api/suites/record", {suite_ref: ref, scale: $("record-scale").value.trim()});
  } catch (e) {
    showRefusal("suite-record", `refused: ${e.message}`);
    return;
  }
  clearRefusals(["suite-record"]);
  app.recordSource = "suite";
  await showRecord(r, t0);
}

// a record loaded (a file or a suite's): the motion chosen, its line, and played
async function showRecord(r, t0) {
  app.record = r;
  $("motion").value = "record";
  $("t-end").value = String(Math.min(120, Math.ceil(r.duration_s + 2)));
  $("record-info").textContent = `${r.name} (${r.title}): ${r.samples} samples, dt = ` +
      `${fmt(r.dt_s, 4)} s, ${fmt(r.duration_s, 2)} s, PGA = ${fmt(r.pga_g)} g` +
      (r.scale !== 1 ? ` (scaled by ${r.scale})` : "") + `, units ${r.units}` +
      (r.warnings.length ? `; ${r.warnings.join("; ")}` : "");
  recordStart = t0;  // timed to the first frame drawn (play)
  await play();
}

async function loadDxf() {
  const file = $("upload-dxf").files[0];
  if (!file) return;
  const params = {units: $("dxf-units").value};
  const layer = $("dxf-layer").value.trim();
  if (layer) params.layer = layer;
  const r = await upload("/api/dxf", file, params);
  if (!r) return;
  state.geometry = r.geometry;
  state.geometryName = r.name;
  state.defects.clear();
  showControls();
  requestStatics(performance.now(), "upload-dxf");
}

let animation = null;
let recordStart = null;  // when a record file was chosen: its first frame is timed

function rot(p, c, th, to) {
  const cs = Math.cos(th), sn = Math.sin(th), dx = p[0] - c[0], dy = p[1] - c[1];
  return [to[0] + cs * dx - sn * dy, to[1] + sn * dx + cs * dy];
}

function drawFrame(res, polys, hingeMarks, k) {
  const f = res.frames[k];
  const [t, phi, row, th1, th2, th3, bx, by, cx, cy] = f;
  const moved = res.drawing.outlines.map((o) => o);
  if (row >= 0) {
    const link = res.chain_links[row];
    const [A, B0, , D] = link.points;
    const maps = [[A, th1, A], [B0, th2, [bx, by]], [D, th3, D]];
    link.links.forEach((idx, j) => {
      const [c, th, to] = maps[j];
      for (const i of idx) moved[i] = res.drawing.outlines[i].map((p) => rot(p, c, th, to));
    });
    const hp = [A, [bx, by], [cx, cy], D];
    hingeMarks.forEach((m, j) => { m.setAttribute("cx", hp[j][0]); m.setAttribute("cy", -hp[j][1]);
                                   m.setAttribute("visibility", "visible"); });
  } else hingeMarks.forEach((m) => m.setAttribute("visibility", "hidden"));
  polys.forEach((p, i) => p.setAttribute("points", pts(moved[i])));
  const collapsed = res.collapsed && res.t_collapse !== null && t >= res.t_collapse;
  const name = row >= 0 ? `${res.chain_links[row].label} open` : "at rest";
  $("anim-title").textContent = `t = ${t.toFixed(2)} s, phi = ${phi >= 0 ? "+" : ""}${phi.toFixed(4)} rad, ` +
      (collapsed ? "COLLAPSED" : name) + (res.exaggerate !== 1 ? ` (rotations drawn x ${res.exaggerate})` : "");
  markFrame(k, t, phi);
}

// the history's marker at (t, phi) (none where phi is unknown) and the frame counters
function markFrame(k, t, phi) {
  if (phi !== null) {
    const m = $("history-marker");
    m.setAttribute("cx", app.hx(t));
    m.setAttribute("cy", app.hy(phi));
  }
  app.frame = k;
  app.frames += 1;
  $("anim-svg").setAttribute("data-frame", k);
}

function drawHistory(res) {
  const svg = $("history-svg");
  svg.replaceChildren();
  const W = 400, H = 160, L = 44, R = 8, T = 10, B = 24;
  const tmax = res.time[res.time.length - 1] || 1;
  const finite = res.phi.filter((v) => v !== null);
  const pmax = Math.max(1e-6, ...finite.map(Math.abs), ...(res.frames || []).map((f) => Math.abs(f[1])));
  const hx = app.hx = (t) => L + (W - L - R) * t / tmax;
  const hy = app.hy = (p) => T + (H - T - B) * (0.5 - 0.5 * p / pmax);
  el("line", {x1: L, x2: W - R, y1: hy(0), y2: hy(0), class: "axis"}, svg);
  el("line", {x1: L, x2: L, y1: T, y2: H - B, class: "axis"}, svg);
  const amax = Math.max(1e-9, ...res.ground.accel_g.map(Math.abs));
  const ga = res.ground.time.map((t, i) => [t, res.ground.accel_g[i]]).filter(([t]) => t <= tmax);
  el("polyline", {class: "accel", points: ga.map(([t, a]) => `${hx(t)},${hy(a / amax * pmax)}`).join(" ")}, svg);
  let d = "", pen = false;
  res.time.forEach((t, i) => {
    const p = res.phi[i];
    if (p === null) { pen = false; return; }
    d += `${pen ? "L" : "M"}${hx(t).toFixed(2)},${hy(p).toFixed(2)}`;
    pen = true;
  });
  el("path", {d, class: "curve"}, svg);
  for (const t of (res.impacts || []).filter((t) => t <= tmax)) {
    el("line", {x1: hx(t), x2: hx(t), y1: H - B, y2: H - B + 5, class: "axis"}, svg);
  }
  const lab = (x, y, s, a = "middle") => { const e = el("text", {x, y, "text-anchor": a}, svg); e.textContent = s; };
  lab(L - 3, hy(pmax) + 3, `${pmax.toFixed(3)}`, "end");
  lab(L - 3, hy(-pmax) + 3, `${(-pmax).toFixed(3)}`, "end");
  lab(L - 3, hy(0) + 3, "0", "end");
  lab(W - R, H - 4, `t [s] (0 to ${tmax.toFixed(2)}); grey: ground motion, ticks: impacts`, "end");
  lab(L + 4, T + 8, "phi [rad]", "start");
  el("circle", {id: "history-marker", r: 3.5, class: "marker", cx: hx(0), cy: hy(0)}, svg);
}

// the engine's frame k: every block turned by theta about its first position and moved
function drawEngineFrame(res, polys, k) {
  const bf = res.block_frames, f = bf.frames[k], t = bf.time[k], phi = bf.phi[k];
  polys.forEach((p, i) => {
    const [dx, dy, th] = f[i], o = bf.origin[i];
    p.setAttribute("points", pts(res.drawing.outlines[i].map((q) => rot(q, o, th, [o[0] + dx, o[1] + dy]))));
  });
  const collapsed = res.collapsed && res.t_collapse !== null && t >= res.t_collapse;
  $("anim-title").textContent = `contact engine: t = ${t.toFixed(2)} s` +
      (phi === null ? "" : `, phi = ${phi >= 0 ? "+" : ""}${phi.toFixed(4)} rad`) + (collapsed ? ", COLLAPSED" : "");
  markFrame(k, t, phi);
}

// what the page says of a response: the model that answered and why, then its outcome
function describeResponse(res) {
  const lab = $("dynamics-label");
  lab.textContent = res.label;
  lab.classList.toggle("invalid", res.valid === false);
  const end = `, the run ends at t = ${fmt(res.t_final, 2)} s`;
  if (res.model === "engine") {
    return `${res.status}: ` + (res.t_collapse !== null ? `collapse at t = ${fmt(res.t_collapse, 3)} s, ` : "") +
        `peak phi = ${fmt(res.peak, 4)} rad${end} (contact engine, friction mu = ${fmt(res.friction, 2)})`;
  }
  const imp = res.impacts.length, law = res.restitution || {};
  // the impact law that ran (momentum where the paper's law does not apply, and why)
  return (res.valid === false ? "not valid here: " : "") +
      `${res.status}: peak phi = ${fmt(res.peak, 4)} rad, ` +
      `${imp} impact${imp === 1 ? "" : "s"}` +
      (res.t_collapse !== null ? `, collapse at t = ${fmt(res.t_collapse, 3)} s` : "") +
      `${end} (${law.model || ""} impacts${law.fallback ? `: ${law.fallback}` : ""})`;
}

function showResponse(res, inputs, t0) {
  app.lastResponse = res;
  app.plays += 1;
  const svg = $("anim-svg");
  drawArch(svg, res.drawing, false);
  const polys = [...svg.querySelectorAll("polygon")];
  const size = 0.012 * svg.viewBox.baseVal.width;
  const engine = res.model === "engine";
  const hingeMarks = engine ? [] : [0, 1, 2, 3].map(() => el("circle", {r: size, class: "hinge-l", visibility: "hidden"}, svg));
  drawHistory(res);
  $("outcome").textContent = describeResponse(res);
  resultShown("response", inputs);
  const times = engine ? res.block_frames.time : res.frames.map((f) => f[0]);
  if (!times.length) return;
  const start = performance.now();
  let first = true;
  const step = () => {
    const t = (performance.now() - start) / 1000;
    let k = times.findIndex((x) => x > t) - 1;
    if (k < 0) k = t >= times[times.length - 1] ? times.length - 1 : 0;
    if (engine) drawEngineFrame(res, polys, k); else drawFrame(res, polys, hingeMarks, k);
    if (first) {
      first = false;
      app.timings.pulse.push(performance.now() - t0);
      if (recordStart !== null) { app.timings.record.push(performance.now() - recordStart); recordStart = null; }
    }
    if (k < times.length - 1) animation = requestAnimationFrame(step);
    else animation = null;
  };
  animation = requestAnimationFrame(step);
}

function playing(on) {
  $("play").disabled = on;
  $("cancel-play").disabled = !on;
}

async function play() {
  const t0 = performance.now();
  if (animation) cancelAnimationFrame(animation);
  const inputs = inputsOf("response");
  let res;
  try {
    const body = {arch: archParams(), ...motionParams(), t_end: $("t-end").value.trim(),
                  exaggerate: Number($("exaggerate").value), dynamics: $("dynamics-model").value};
    if (friction() !== "") body.friction = friction();
    res = await post("/api/respond", body);
  } catch (e) {
    recordStart = null;
    if (!e.handled) console.warn(e);
    else if (e.status === 400) showRefusal(fieldControl(e.message) || "play", `refused: ${e.message}`);
    else showRefusal("play", e.message);
    return;
  }
  clearError();
  clearRefusals(["play", ...Object.values(FIELD_CONTROLS)].filter((id) => !STATICS_CONTROLS.includes(id)));
  if (!res.job) { showResponse(res, inputs, t0); return; }
  // the contact engine answers this arch: a job of the server (seconds to minutes)
  app.responseJob = res.job;
  const lab = $("dynamics-label");
  lab.textContent = res.label;
  lab.classList.remove("invalid");
  playing(true);
  const poll = async () => {
    let s;
    try { s = await jobStatus(res.job.id); } catch (e) { showError(`engine: ${e.message}`); playing(false); return; }
    app.responseJob = s;
    if (s.state === "running") {
      // progress in tenths of a simulated second (the run ends at collapse, at rest or at most there)
      $("outcome").textContent = "contact engine running" + (s.total > 1 ?
          `: t = ${(s.done / 10).toFixed(1)} s of at most ${(s.total / 10).toFixed(1)} s simulated` : "") +
          `, ${s.elapsed_s.toFixed(1)} s`;
      setTimeout(poll, 200);
      return;
    }
    playing(false);
    if (s.state === "done") showResponse({...s.result, job: s.id}, inputs, t0);
    else if (s.state === "cancelled") $("outcome").textContent = "contact engine cancelled";
    else { showError(s.error); $("outcome").textContent = ""; }
  };
  $("outcome").textContent = "contact engine starting ...";
  setTimeout(poll, 150);
}
