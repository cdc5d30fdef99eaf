// archrock app: the page. Plain JS + SVG, no library, no build step. Every number shown comes
// from the server's JSON API (the library's own functions); this script only draws.
"use strict";

const SVGNS = "http://www.w3.org/2000/svg";
const DEG = Math.PI / 180;
// Oppenheim's arch: R = 10 m, embrace 157.5 deg, t = 1.5 m, 7 voussoirs (span, rise of the centreline)
const OPPENHEIM = {shape: "circular", span: 20 * Math.sin(78.75 * DEG),
                   rise: 10 * (1 - Math.cos(78.75 * DEG)), thickness: 1.5, voussoirs: 7,
                   joints: "normal"};

const state = {...OPPENHEIM, geometry: null, geometryName: null, defects: new Set(),
               showRange: false};
// measurements and counters read by the tests (performance.now(), ms)
const app = window.__app = {redraws: 0, frame: -1, frames: 0, timings: {slider: [], pulse: [],
                            ensemble: [], record: [], png: []}, lastLimit: null,
                            lastResponse: null, job: null, record: null, report: null, plays: 0};
// the largest file the server reads (uploads.MAX_FILE_BYTES)
const MAX_FILE_BYTES = 20e6;

const $ = (id) => document.getElementById(id);
// the token the server wrote into this page at launch: every API call carries it (another
// site's page cannot read it, so it cannot drive the app)
const TOKEN = document.querySelector('meta[name="archrock-token"]').content;
const api = (url, init = {}) => fetch(url, {...init, credentials: "same-origin",
                                           headers: {...(init.headers || {}),
                                                     "X-Archrock-Token": TOKEN}});

function el(tag, attrs, parent) {
  const e = document.createElementNS(SVGNS, tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

function fmt(x, d = 3) { return x === null || x === undefined ? "–" : Number(x).toFixed(d); }

// ------------------------------------------------------------------ messages and requests
function showError(msg) {
  const m = $("message");
  m.textContent = msg;
  m.hidden = false;
}
function clearError() { $("message").hidden = true; $("message").textContent = ""; }

async function post(url, body) {
  let resp;
  try {
    resp = await api(url, {method: "POST", headers: {"Content-Type": "application/json"},
                             body: JSON.stringify(body)});
  } catch (e) {
    showError("the archrock server does not answer (is `archrock app` still running?)");
    throw e;
  }
  const data = await resp.json().catch(() => ({error: `HTTP ${resp.status}`}));
  if (!resp.ok) {
    showError(data.error || `HTTP ${resp.status}`);
    const err = new Error(data.error);
    err.handled = true;
    err.status = resp.status;
    throw err;
  }
  return data;
}

// ------------------------------------------------------------------ refusals beside their control
// the element a refusal is shown after: the control's label (or the control itself)
function anchorOf(id) {
  const c = $(id);
  if (!c) return null;
  return c.closest("label") || c;
}

function showRefusal(id, msg) {
  const a = anchorOf(id);
  if (!a) return false;
  let r = $(`refusal-${id}`);
  if (!r) {
    r = document.createElement("div");
    r.id = `refusal-${id}`;
    r.className = "refusal";
    r.setAttribute("role", "alert");
    a.insertAdjacentElement("afterend", r);
  }
  r.textContent = msg;
  return true;
}

function clearRefusals(ids) {
  for (const id of ids) { const r = $(`refusal-${id}`); if (r) r.remove(); }
}

// the control of a field the server names ("span: ...", "unknown field 'arch.span'")
const FIELD_CONTROLS = {shape: "shape", span: "span", rise: "rise", thickness: "thickness",
                        thickness_crown: "thickness", voussoirs: "voussoirs", joints: "joints",
                        pier_height: "pier-height", pier_width: "pier-width",
                        pier_courses: "pier-height", friction: "friction-mu", geometry: "upload",
                        defects: "arch-svg", kind: "pulse-kind", amplitude: "amplitude",
                        duration: "duration", t_end: "t-end", exaggerate: "exaggerate",
                        dynamics: "dynamics-model", record: "record-file"};

function fieldControl(msg) {
  const m = /^unknown field '(?:[a-z]+\.)?([a-z_]+)'/.exec(msg || "") || /^([a-z_]+):/.exec(msg || "");
  return m ? FIELD_CONTROLS[m[1]] || null : null;
}

function archParams(withDefects = true) {
  const defects = withDefects ? [...state.defects].sort((a, b) => a - b)
                                  .map((i) => `${i}:thickness=0.5`) : [];
  const piers = {};
  const h = $("pier-height").value.trim(), w = $("pier-width").value.trim();
  if (h !== "" || w !== "") Object.assign(piers, {pier_height: h || null, pier_width: w || null});
  if (state.geometry) return {geometry: state.geometry, name: state.geometryName, defects, ...piers};
  return {shape: state.shape, span: state.span, rise: state.rise, thickness: state.thickness,
          voussoirs: state.voussoirs, joints: state.joints, defects, ...piers};
}

// ------------------------------------------------------------------ results that match their inputs
// each result keeps the inputs it was computed from; once they differ from the page's, it is
// greyed with a note (and shown again as it was if the inputs come back)
function friction() { return $("friction-mu").value.trim(); }
function inputsOf(name) {
  const common = {arch: archParams(), seed: $("seed").value.trim(), spreads: spreadsParams()};
  if (name === "response") {
    const rec = $("motion").value === "record";
    return {arch: common.arch, motion: rec ? {record: app.record && app.record.id} : {pulse: pulseParams()},
            t_end: $("t-end").value.trim(), exaggerate: $("exaggerate").value, friction: friction(),
            dynamics: $("dynamics-model").value};
  }
  if (name === "ensemble") return {...common, samples: $("samples").value.trim(),
                                   pulse: $("with-pulse").checked ? pulseParams() : null,
                                   friction: $("with-pulse").checked ? friction() : null};
  if (name === "curve") return {...common, samples: $("curve-samples").value.trim(), friction: friction(),
                                durations: $("curve-durations").value.trim(), kind: $("pulse-kind").value};
  return {...common, samples: $("report-samples").value.trim(), contact: $("report-contact").checked};
}
const RESULTS = {response: ["anim-title", "anim-svg", "history-svg", "dynamics-label", "outcome"],
                 ensemble: ["hist-svg", "ensemble-result"], curve: ["curve-svg", "curve-result"],
                 report: ["report-status"]};
const shown = {};  // name -> the JSON of the inputs of the result shown

function resultShown(name, inputs) { shown[name] = JSON.stringify(inputs); markStale(); }

function markStale() {
  for (const [name, ids] of Object.entries(RESULTS)) {
    const stale = shown[name] !== undefined && shown[name] !== JSON.stringify(inputsOf(name));
    for (const id of ids) $(id).classList.toggle("stale", stale);
    let note = $(`stale-${name}`);
    if (stale && !note) {
      note = document.createElement("div");
      note.id = `stale-${name}`;
      note.className = "stale-note";
      note.textContent = "inputs changed: run again (the result below is of the earlier inputs)";
      $(ids[0]).insertAdjacentElement("beforebegin", note);
    } else if (!stale && note) note.remove();
  }
}

// ------------------------------------------------------------------ drawing helpers
function bounds(outlines) {
  let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
  for (const o of outlines) for (const [x, y] of o) {
    x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
  }
  return {x0, x1, y0, y1};
}

function setView(svg, drawing) {
  const b = bounds(drawing.outlines);
  const pad = 0.08 * Math.max(b.x1 - b.x0, b.y1 - b.y0);
  const y0 = Math.min(b.y0, drawing.ground);
  // y up: points are drawn at (x, -y)
  svg.setAttribute("viewBox", `${b.x0 - pad} ${-b.y1 - pad} ${b.x1 - b.x0 + 2 * pad} ${b.y1 - y0 + 2 * pad}`);
  return {b, pad, y0};
}

function pts(poly) { return poly.map(([x, y]) => `${x},${-y}`).join(" "); }

function drawArch(svg, drawing, interactive) {
  svg.replaceChildren();
  const {b, pad} = setView(svg, drawing);
  el("line", {x1: b.x0 - pad, x2: b.x1 + pad, y1: -drawing.ground, y2: -drawing.ground,
              class: "ground"}, svg);
  const g = el("g", {class: "voussoirs"}, svg);
  drawing.outlines.forEach((o, i) => {
    const p = el("polygon", {points: pts(o), class: "voussoir" +
                             (interactive && state.defects.has(i) ? " defect" : ""),
                             "data-index": i}, g);
    if (interactive) {
      const t = el("title", {}, p);
      t.textContent = `voussoir ${i}: click to thin it to half its thickness`;
      p.addEventListener("click", () => toggleDefect(i));
    }
  });
  return g;
}

// ------------------------------------------------------------------ statics
let inFlight = false, pending = null;
// the inputs of the arch drawn (the last the server accepted): restored when a change is refused
let lastValid = null;
const STATICS_CONTROLS = ["shape", "span", "rise", "thickness", "voussoirs", "joints", "typed-value",
                          "pier-height", "friction-mu", "upload", "upload-dxf", "arch-svg"];

function archInputs() {
  return {state: {shape: state.shape, span: state.span, rise: state.rise, thickness: state.thickness,
                  voussoirs: state.voussoirs, joints: state.joints, geometry: state.geometry,
                  geometryName: state.geometryName, defects: new Set(state.defects),
                  showRange: state.showRange},
          dom: {"pier-height": $("pier-height").value, "pier-width": $("pier-width").value,
                "friction-mu": $("friction-mu").value}};
}

function restoreInputs(saved) {
  Object.assign(state, saved.state, {defects: new Set(saved.state.defects)});
  for (const [id, v] of Object.entries(saved.dom)) $(id).value = v;
  $("show-range").checked = state.showRange;
  showControls();
  markStale();
}

// cause: the id of the control whose change asked for this (the refusal is shown beside it)
function requestStatics(t0, cause = null) {
  // coalesce: while one request runs, keep only the newest input (and its earliest start time)
  if (pending) { pending.t0 = Math.min(pending.t0, t0); pending.cause = cause || pending.cause; }
  else pending = {t0, cause};
  markStale();
  if (!inFlight) runStatics();
}

async function runStatics() {
  const job = pending;
  pending = null;
  inFlight = true;
  try {
    const body = {arch: archParams(), thrust_range: state.showRange};
    const mu = $("friction-mu").value.trim();
    if (mu !== "") body.friction = mu;
    const calls = [post("/api/limit", body)];
    if (state.defects.size) calls.push(post("/api/limit", {arch: archParams(false)}));
    const [res, base] = await Promise.all(calls);
    clearError();
    clearRefusals(STATICS_CONTROLS);
    lastValid = archInputs();
    drawStatics(res, base);
    requestAnimationFrame(() => {
      const dt = performance.now() - job.t0;
      app.timings.slider.push(dt);
      (app.timings.sliderServer = app.timings.sliderServer || []).push(res.elapsed_ms);
      app.lastLimitMs = dt;
    });
  } catch (e) {
    if (!e.handled) console.warn(e);
    else if (e.status === 400) refuseStatics(e.message, job.cause);
  } finally {
    inFlight = false;
    if (pending) runStatics();
  }
}

// a refused arch: its message beside the control that caused it, and the page back to the last
// arch the server accepted (the drawing, k and the controls agree; never a default arch)
function refuseStatics(msg, cause) {
  const id = cause || fieldControl(msg) || "shape";
  clearRefusals(STATICS_CONTROLS);
  if (lastValid) {
    restoreInputs(lastValid);
    showRefusal(id, `refused: ${msg}; the page shows the last valid arch`);
  } else showRefusal(id, `refused: ${msg}`);
  app.refusals = (app.refusals || 0) + 1;
}

function drawStatics(res, base) {
  app.lastLimit = res;
  const s = res.summary;
  const svg = $("arch-svg");
  drawArch(svg, res.drawing, true);
  for (const [key, cls] of [["min", "thrust-min"], ["max", "thrust-max"], ["r", "thrust-r"],
                            ["l", "thrust-l"]]) {
    if (res.thrust_lines[key]) el("polyline", {points: pts(res.thrust_lines[key]), class: cls,
                                              id: `thrust-${key}`}, svg);
  }
  for (const d of ["l", "r"]) {
    for (const h of res.hinges[d]) {
      const size = 0.012 * (svg.viewBox.baseVal.width || 20);
      el("circle", {cx: h.point[0], cy: -h.point[1], r: size, class: `hinge-${d}`}, svg);
    }
  }
  app.redraws += 1;
  svg.setAttribute("data-redraws", app.redraws);
  svg.setAttribute("data-k", s.k);
  // the blocks said as what they are: a pier's courses are not voussoirs
  const d = res.drawing;
  $("arch-name").textContent = `${d.name} (${d.voussoirs} voussoirs` +
    (d.pier_courses ? `, ${d.pier_courses} pier courses)` : ")");
  $("k").textContent = `k = ${fmt(s.k)}`;
  $("k-detail").textContent = `k_l = ${fmt(s.k_l, 4)} g, k_r = ${fmt(s.k_r, 4)} g` +
      (s.four_link_holds ? "" : " (four-link model does not hold)");
  const ml = s.mechanism_l, mr = s.mechanism_r;
  $("mechanisms").textContent = `M_l: ${ml.kind} ${ml.label}; M_r: ${mr.kind} ${mr.label}`;
  const fl = s.friction_needed_l, fr = s.friction_needed_r;
  $("friction").textContent = fl !== undefined ?
      `friction the collapse needs: mu = ${fmt(fl)} (l), ${fmt(fr)} (r)` : "";
  $("thrust").textContent = s.thrust_min ?
      `thrust range: H = ${fmt(s.thrust_min.H / 1e3, 1)} to ${fmt(s.thrust_max.H / 1e3, 1)} kN/m` : "";
  $("friction-k").textContent = s.friction_mu !== undefined ?
      `with friction mu = ${fmt(s.friction_mu)}: k_l = ${fmt(s.friction_k_l, 4)} g, ` +
      `k_r = ${fmt(s.friction_k_r, 4)} g` +
      (s.sliding_governs_l || s.sliding_governs_r ? " (sliding governs)" : "") : "";
  if (base && state.defects.size) {
    const b = base.summary.k;
    $("defect-loss").textContent = `defects: k ${fmt(b)} → ${fmt(s.k)} ` +
        `(${fmt(100 * (s.k - b) / b, 1)} %)`;
  } else $("defect-loss").textContent = "";
}

function toggleDefect(i) {
  if (state.defects.has(i)) state.defects.delete(i); else state.defects.add(i);
  requestStatics(performance.now(), "arch-svg");
}

// ------------------------------------------------------------------ the controls
const FIELDS = ["span", "rise", "thickness", "voussoirs"];

function showControls() {
  $("shape").value = state.shape;
  $("joints").value = state.joints;
  for (const f of FIELDS) {
    const v = state[f];
    if (typeof v === "number") $(f).value = v;
    $(`${f}-out`).textContent = typeof v === "number" ? (f === "voussoirs" ? v : v.toFixed(3)) : v;
  }
  const disabled = state.geometry !== null;
  for (const id of [...FIELDS, "shape", "joints"]) $(id).disabled = disabled;
}

function leaveGeometryFile() {
  if (state.geometry) { state.geometry = null; state.geometryName = null; }
}

function bindControls() {
  for (const f of FIELDS) {
    $(f).addEventListener("input", (ev) => {
      const t0 = performance.now();
      leaveGeometryFile();
      state[f] = f === "voussoirs" ? parseInt(ev.target.value, 10) : parseFloat(ev.target.value);
      if (f === "voussoirs") state.defects.clear();
      showControls();
      requestStatics(t0, f);
    });
  }
  for (const f of ["shape", "joints"]) {
    $(f).addEventListener("change", (ev) => {
      leaveGeometryFile();
      state[f] = ev.target.value;
      requestStatics(performance.now(), f);
    });
  }
  $("typed-apply").addEventListener("click", () => {
    const f = $("typed-field").value, text = $("typed-value").value.trim();
    leaveGeometryFile();
    const v = Number(text);
    // sent as typed when it is not a number: the server's message names the field
    state[f] = text !== "" && Number.isFinite(v) ? v : text;
    showControls();
    requestStatics(performance.now(), "typed-value");
  });
  $("oppenheim").addEventListener("click", () => {
    Object.assign(state, OPPENHEIM, {geometry: null, geometryName: null});
    state.defects.clear();
    showControls();
    requestStatics(performance.now());
  });
  for (const id of ["pier-height", "pier-width", "friction-mu"]) {
    $(id).addEventListener("change", () => requestStatics(performance.now(),
                                                          id === "pier-width" ? "pier-height" : id));
  }
  $("show-range").addEventListener("change", (ev) => {
    state.showRange = ev.target.checked;
    requestStatics(performance.now());
  });
  $("upload").addEventListener("change", async (ev) => {
    const file = ev.target.files[0];
    if (!file) return;
    if (file.size > 2e6) { showError(`${file.name}: larger than 2 MB`); return; }
    let data;
    try { data = JSON.parse(await file.text()); } catch (e) {
      showError(`${file.name}: not a JSON geometry file (${e.message})`);
      return;
    }
    state.geometry = data;
    state.geometryName = file.name.replace(/\.json$/i, "");
    state.defects.clear();
    showControls();
    requestStatics(performance.now(), "upload");
  });
  for (const b of document.querySelectorAll("button.export")) {
    b.addEventListener("click", () => download(b.dataset.what));
  }
  $("export-svg").addEventListener("click", exportSvg);
  for (const b of document.querySelectorAll("button.png")) {
    b.addEventListener("click", () => exportPng(b.dataset.svg, b.dataset.name));
  }
  $("record-file").addEventListener("change", loadRecord);
  for (const id of ["record-units", "record-scale"]) $(id).addEventListener("change", loadRecord);
  $("upload-dxf").addEventListener("change", loadDxf);
  $("run-report").addEventListener("click", runReport);
  $("cancel-report").addEventListener("click", () => {
    if (app.report && app.report.state === "running") {
      post(`/api/jobs/${app.report.id}/cancel`, {}).catch(() => null);
    }
  });
  $("play").addEventListener("click", play);
  $("cancel-play").addEventListener("click", () => {
    if (app.responseJob && app.responseJob.state === "running") {
      post(`/api/jobs/${app.responseJob.id}/cancel`, {}).catch(() => null);
    }
  });
  // any input changed: the results of other inputs are greyed at once
  document.addEventListener("input", markStale);
  document.addEventListener("change", markStale);
  $("run-ensemble").addEventListener("click", runEnsemble);
  $("run-curve").addEventListener("click", runCurve);
  $("cancel-ensemble").addEventListener("click", cancelEnsemble);
}

// ------------------------------------------------------------------ export
function saveBlob(blob, name) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

async function download(what) {
  let motion;
  try { motion = what === "response-csv" ? motionParams() : {pulse: pulseParams()}; } catch (e) { return; }
  const body = {what, arch: archParams(), ...motion, t_end: $("t-end").value};
  if (friction() !== "") body.friction = friction();
  let url = "/api/export", init = {method: "POST", headers: {"Content-Type": "application/json"},
                                   body: JSON.stringify(body)};
  if (what === "response-csv") {
    body.dynamics = $("dynamics-model").value;
    init.body = JSON.stringify(body);
    const last = app.lastResponse;
    // the contact engine's response is its job's file, while it still matches the inputs
    if (last && last.model === "engine" && shown.response === JSON.stringify(inputsOf("response"))) {
      url = `/api/jobs/${last.job}/download`;
      init = {};
    }
  }
  const resp = await api(url, init);
  if (!resp.ok) {
    const data = await resp.json().catch(() => ({}));
    showError(data.error || `HTTP ${resp.status}`);
    return;
  }
  clearError();
  const name = (resp.headers.get("Content-Disposition") || "").match(/filename="([^"]+)"/);
  saveBlob(await resp.blob(), name ? name[1] : what);
}

// a figure of the page as a stand-alone SVG document: its drawing, the style rules of its
// classes and text, and its size on the screen [px]
function figureSvg(id) {
  const src = $(id);
  const box = src.getBoundingClientRect();
  const w = Math.max(1, Math.round(box.width)), h = Math.max(1, Math.round(box.height));
  const svg = src.cloneNode(true);
  svg.setAttribute("xmlns", SVGNS);
  svg.setAttribute("width", w);
  svg.setAttribute("height", h);
  const style = document.createElementNS(SVGNS, "style");
  style.textContent = [...document.styleSheets[0].cssRules].map((r) => r.cssText)
      .filter((t) => /^(\.[a-z]|text\b)/.test(t)).join("\n");
  svg.insertBefore(style, svg.firstChild);
  return {text: new XMLSerializer().serializeToString(svg), w, h};
}

function exportSvg() {
  saveBlob(new Blob([figureSvg("arch-svg").text], {type: "image/svg+xml"}), "arch.svg");
}

// PNG in the browser: the SVG drawn on a canvas (twice its screen size, white ground)
async function exportPng(id, name) {
  const t0 = performance.now();
  const {text, w, h} = figureSvg(id);
  const url = URL.createObjectURL(new Blob([text], {type: "image/svg+xml"}));
  try {
    const img = new Image();
    img.src = url;
    await img.decode();
    const scale = 2, canvas = document.createElement("canvas");
    canvas.width = w * scale;
    canvas.height = h * scale;
    const ctx = canvas.getContext("2d");
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
    const blob = await new Promise((ok) => canvas.toBlob(ok, "image/png"));
    if (!blob) throw new Error("the browser made no PNG");
    saveBlob(blob, name);
    app.timings.png.push(performance.now() - t0);
  } catch (e) {
    showError(`PNG export of ${name}: ${e.message || e}`);
  } finally {
    URL.revokeObjectURL(url);
  }
}

// ------------------------------------------------------------------ dynamics
function pulseParams() {
  return {kind: $("pulse-kind").value, amplitude: $("amplitude").value.trim(),
          duration: $("duration").value.trim()};
}

// the ground motion of a response: {pulse} or, when chosen and loaded, {record: {id}}
function motionParams() {
  if ($("motion").value === "record") {
    if (!app.record) {
      showError("record: open a record file first (PEER .AT2 or two columns 'time accel')");
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
  if (!resp.ok) { showError(data.error || `HTTP ${resp.status}`); return null; }
  clearError();
  return data;
}

async function loadRecord() {
  const file = $("record-file").files[0];
  if (!file) return;
  const t0 = performance.now();
  const r = await upload("/api/record", file, {units: $("record-units").value,
                                               scale: $("record-scale").value.trim()});
  if (!r) return;
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
  const m = $("history-marker");
  m.setAttribute("cx", app.hx(t));
  m.setAttribute("cy", app.hy(phi));
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
  if (phi !== null) {
    const m = $("history-marker");
    m.setAttribute("cx", app.hx(t));
    m.setAttribute("cy", app.hy(phi));
  }
  app.frame = k;
  app.frames += 1;
  $("anim-svg").setAttribute("data-frame", k);
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

// ------------------------------------------------------------------ ensemble
let polling = null;

function spreadsParams() {
  return {span: $("spread-span").value.trim(), thickness: $("spread-thickness").value.trim(),
          radius: $("spread-radius").value.trim()};
}

async function runEnsemble() {
  const t0 = performance.now();
  const body = {arch: archParams(), samples: $("samples").value.trim(), seed: $("seed").value.trim(),
                spreads: spreadsParams()};
  if ($("with-pulse").checked) body.pulse = pulseParams();
  if (body.pulse && friction() !== "") body.friction = friction();
  const inputs = inputsOf("ensemble");
  $("hist-svg").replaceChildren();
  $("ensemble-result").textContent = "";
  delete shown.ensemble;
  markStale();
  runJob("/api/ensemble", body, "arches", $("ensemble-result"), (s) => {
    drawHistogram(s.result);
    resultShown("ensemble", inputs);
    app.timings.ensemble.push({samples: s.total, ms: performance.now() - t0, server_s: s.result.wall_s});
  });
}

async function runCurve() {
  const body = {arch: archParams(), samples: $("curve-samples").value.trim(), seed: $("seed").value.trim(),
                spreads: spreadsParams(), durations: $("curve-durations").value.trim(),
                kind: $("pulse-kind").value};
  if (friction() !== "") body.friction = friction();
  const inputs = inputsOf("curve");
  $("curve-svg").replaceChildren();
  $("curve-result").textContent = "";
  delete shown.curve;
  markStale();
  runJob("/api/curve", body, "arch-durations", $("curve-result"), (s) => {
    drawCurve(s.result);
    resultShown("curve", inputs);
  });
}

// a job's status from the server (an Error with the server's message when it answers one)
async function jobStatus(id) {
  const resp = await api(`/api/jobs/${id}`);
  const s = await resp.json();
  if (!resp.ok) throw new Error(s.error);
  return s;
}

// a background job: start it, poll its progress, then onDone(status) or say why it stopped
// the controls of a job request's own fields (the arch's are those of FIELD_CONTROLS)
const JOB_CONTROLS = {
  "/api/ensemble": {samples: "samples", seed: "seed", span: "spread-span", thickness: "spread-thickness",
                    radius: "spread-radius", spreads: "spread-span", button: "run-ensemble"},
  "/api/curve": {samples: "curve-samples", seed: "seed", span: "spread-span", thickness: "spread-thickness",
                 radius: "spread-radius", spreads: "spread-span", durations: "curve-durations",
                 button: "run-curve"},
  "/api/report": {samples: "report-samples", seed: "seed", span: "spread-span",
                  thickness: "spread-thickness", radius: "spread-radius", spreads: "spread-span",
                  button: "run-report"}};

// a refused job request: its message beside the control of the field it names
function refuseJob(url, e) {
  const own = JOB_CONTROLS[url];
  const ids = Object.values(own);
  clearRefusals(ids);
  if (!e.handled) return;
  // 422: a valid request with no answer of the kind asked (the four-link model does not hold)
  if (e.status !== 400) { showRefusal(own.button, e.message); return; }
  const m = /^unknown field '(?:[a-z]+\.)?([a-z_]+)'/.exec(e.message || "") || /^([a-z_]+):/.exec(e.message || "");
  showRefusal((m && own[m[1]]) || own.button, `refused: ${e.message}`);
}

async function runJob(url, body, unit, said, onDone) {
  let job;
  try { job = await post(url, body); } catch (e) { if (!e.handled) console.warn(e); refuseJob(url, e); return; }
  clearRefusals(Object.values(JOB_CONTROLS[url]));
  clearError();
  app.job = job;
  for (const id of ["run-ensemble", "run-curve"]) $(id).disabled = true;
  $("cancel-ensemble").disabled = false;
  const poll = async () => {
    let s;
    try { s = await jobStatus(job.id); } catch (e) { showError(`job: ${e.message}`); finish(); return; }
    app.job = s;
    $("progress").value = s.total ? s.done / s.total : 0;
    $("progress-text").textContent = `${s.done} / ${s.total} ${unit}, ${s.elapsed_s.toFixed(1)} s`;
    if (s.state === "running") { polling = setTimeout(poll, 150); return; }
    finish();
    if (s.state === "done") onDone(s);
    else if (s.state === "cancelled") said.textContent = `cancelled after ${s.done} of ${s.total} ${unit}`;
    else showError(s.error);
  };
  const finish = () => {
    for (const id of ["run-ensemble", "run-curve"]) $(id).disabled = false;
    $("cancel-ensemble").disabled = true;
  };
  polling = setTimeout(poll, 100);
}

async function cancelEnsemble() {
  if (app.job) await post(`/api/jobs/${app.job.id}/cancel`, {}).catch(() => null);
}

// the assessment report: `archrock assess` of the arch shown, a job on the server; its HTML
// file is downloaded when it is done
async function runReport() {
  const body = {arch: archParams(), samples: $("report-samples").value.trim(),
                seed: $("seed").value.trim(), spreads: spreadsParams(),
                contact: $("report-contact").checked};
  const t0 = performance.now();
  const inputs = inputsOf("report");
  let job;
  try { job = await post("/api/report", body); } catch (e) {
    if (!e.handled) console.warn(e);
    refuseJob("/api/report", e);
    return;
  }
  clearRefusals(Object.values(JOB_CONTROLS["/api/report"]));
  clearError();
  app.report = job;
  delete shown.report;
  markStale();
  const said = $("report-status");
  said.textContent = `computing the report (about ${Math.max(1, Math.round(job.estimate_s + 2))} s) ...`;
  $("run-report").disabled = true;
  $("cancel-report").disabled = false;
  const finish = () => { $("run-report").disabled = false; $("cancel-report").disabled = true; };
  const poll = async () => {
    let s;
    try { s = await jobStatus(job.id); } catch (e) { showError(`report: ${e.message}`); finish(); return; }
    app.report = s;
    if (s.state === "running") {
      said.textContent = `computing the report: ${s.done} of ${s.total} steps, ${s.elapsed_s.toFixed(1)} s`;
      setTimeout(poll, 200);
      return;
    }
    finish();
    if (s.state === "cancelled") { said.textContent = "report cancelled"; return; }
    if (s.state !== "done") { showError(s.error); said.textContent = ""; return; }
    const resp = await api(`/api/jobs/${job.id}/download`);
    if (!resp.ok) { showError(`report: HTTP ${resp.status}`); return; }
    const name = (resp.headers.get("Content-Disposition") || "").match(/filename="([^"]+)"/);
    saveBlob(await resp.blob(), name ? name[1] : "assessment.html");
    const r = s.result;
    said.textContent = `report of ${r.name}: k = ${fmt(r.k)}, ${r.sections.length} sections, ` +
        `${(r.bytes / 1e6).toFixed(1)} MB, ${r.seconds.toFixed(1)} s on the server`;
    app.timings.report = performance.now() - t0;
    resultShown("report", inputs);
  };
  setTimeout(poll, 200);
}

function drawHistogram(result) {
  const svg = $("hist-svg");
  svg.replaceChildren();
  const {edges, counts} = result.histogram;
  const W = 600, H = 170, L = 36, R = 8, T = 10, B = 28;
  if (!counts.length) { $("ensemble-result").textContent = "no arch stood: no histogram"; return; }
  const x0 = edges[0], x1 = edges[edges.length - 1], cmax = Math.max(...counts);
  const hx = (x) => L + (W - L - R) * (x - x0) / Math.max(1e-12, x1 - x0);
  const hy = (c) => H - B - (H - T - B) * c / cmax;
  counts.forEach((c, i) => el("rect", {x: hx(edges[i]), y: hy(c), width: Math.max(0.5, hx(edges[i + 1]) - hx(edges[i])),
                                       height: H - B - hy(c), class: "bar"}, svg));
  const s = result.summary;
  const k0 = Math.min(s.nominal.k_l, s.nominal.k_r);
  if (k0 >= x0 && k0 <= x1) el("line", {x1: hx(k0), x2: hx(k0), y1: T, y2: H - B, class: "nominal"}, svg);
  el("line", {x1: L, x2: W - R, y1: H - B, y2: H - B, class: "axis"}, svg);
  const lab = (x, y, t, a = "middle") => { const e = el("text", {x, y, "text-anchor": a}, svg); e.textContent = t; };
  for (let i = 0; i <= 4; i++) {
    const v = x0 + (x1 - x0) * i / 4;
    lab(hx(v), H - B + 12, v.toFixed(3), i === 0 ? "start" : i === 4 ? "end" : "middle");
  }
  lab(W - R, H - 3, "k = min(k_l, k_r) [g]; dashed: the nominal arch", "end");
  lab(L - 3, hy(cmax) + 3, `${cmax}`, "end");
  svg.setAttribute("data-bars", counts.length);
  const km = s.k_min;
  let text = `${s.samples} arches: k mean ${fmt(km.mean)}, 5-95% ${fmt(km.q05)} to ${fmt(km.q95)} ` +
             `(nominal ${fmt(k0)}); failed ${s.failed.count}`;
  if (s.p_collapse) {
    const p = s.p_collapse;
    text += p.p === null ? `; P(collapse): ${p.note}` :
        `; P(collapse) = ${fmt(p.p)} (95% interval ${fmt(p.low)} to ${fmt(p.high)}, ${p.collapses} of ${p.trials})`;
  }
  text += `; ${result.wall_s.toFixed(2)} s on the server`;
  $("ensemble-result").textContent = text;
}

function drawCurve(r) {
  const svg = $("curve-svg");
  svg.replaceChildren();
  const W = 600, H = 200, L = 40, R = 10, T = 10, B = 30;
  const all = [...r.nominal_g, ...r.q05_g, ...r.q50_g, ...r.q95_g].filter((v) => v !== null);
  if (!all.length) { $("curve-result").textContent = "no collapse up to 10 g at these durations"; return; }
  const d0 = 0, d1 = Math.max(...r.durations), amax = Math.min(10, 1.05 * Math.max(...all));
  const cx = (d) => L + (W - L - R) * (d - d0) / (d1 - d0);
  const cy = (a) => T + (H - T - B) * (1 - Math.min(a, amax) / amax);
  el("line", {x1: L, x2: W - R, y1: H - B, y2: H - B, class: "axis"}, svg);
  el("line", {x1: L, x2: L, y1: T, y2: H - B, class: "axis"}, svg);
  const ok = r.durations.map((d, i) => r.q05_g[i] !== null && r.q95_g[i] !== null);
  const up = r.durations.filter((d, i) => ok[i]).map((d) => [d, r.q95_g[r.durations.indexOf(d)]]);
  const lo = r.durations.filter((d, i) => ok[i]).map((d) => [d, r.q05_g[r.durations.indexOf(d)]]);
  if (up.length > 1) {
    el("polygon", {class: "band", points: [...up, ...lo.reverse()].map(([d, a]) => `${cx(d)},${cy(a)}`).join(" ")}, svg);
  }
  const line = (vals, cls) => {
    const p = r.durations.map((d, i) => [d, vals[i]]).filter(([, a]) => a !== null);
    el("polyline", {class: cls, points: p.map(([d, a]) => `${cx(d)},${cy(a)}`).join(" ")}, svg);
    return p;
  };
  line(r.q50_g, "median");
  for (const [d, a] of line(r.nominal_g, "nominal-curve")) el("circle", {cx: cx(d), cy: cy(a), r: 2.5, class: "marker"}, svg);
  const lab = (x, y, t, a = "middle") => { const e = el("text", {x, y, "text-anchor": a}, svg); e.textContent = t; };
  for (const d of r.durations) lab(cx(d), H - B + 12, `${d}`);
  for (let i = 0; i <= 4; i++) lab(L - 3, cy(amax * i / 4) + 3, (amax * i / 4).toFixed(2), "end");
  lab(W - R, H - 3, "pulse duration t_p [s]", "end");
  lab(L + 4, T + 8, "collapse amplitude |a| [g]: nominal (dots), median (dashed), 5-95% band", "start");
  svg.setAttribute("data-points", r.durations.length);
  $("curve-result").textContent = `${r.kind} pulse: ${r.n_used} of ${r.samples} arches used` +
      (r.left_out ? ` (${r.left_out} left out)` : "") + `; ${r.wall_s.toFixed(1)} s on the server`;
}

// ------------------------------------------------------------------ start
bindControls();
showControls();
requestStatics(performance.now());
