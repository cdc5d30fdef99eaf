// archrock app: the page. Plain JS + SVG, no library, no build step. Every number shown comes
// from the server's JSON API (the library's own functions); this script only draws. The arch,
// statics, refusals and exports here; dynamics.js and studies.js (loaded first) the rest.
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
                        fc: "fc",
                        defects: "arch-svg", kind: "pulse-kind", amplitude: "amplitude",
                        duration: "duration", t_end: "t-end", exaggerate: "exaggerate",
                        dynamics: "dynamics-model", record: "record-file",
                        suite_ref: "suite-record", suite: "record-suite"};

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
  const fc = $("fc").value.trim();
  if (fc !== "") piers.fc = fc;  // the masonry's strength [MPa]; empty: infinite (Heyman)
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
  return {...common, samples: $("report-samples").value.trim(), contact: $("report-contact").checked,
          friction: friction()};
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
                          "pier-height", "friction-mu", "fc", "upload", "upload-dxf", "arch-svg"];

function archInputs() {
  return {state: {shape: state.shape, span: state.span, rise: state.rise, thickness: state.thickness,
                  voussoirs: state.voussoirs, joints: state.joints, geometry: state.geometry,
                  geometryName: state.geometryName, defects: new Set(state.defects),
                  showRange: state.showRange},
          dom: {"pier-height": $("pier-height").value, "pier-width": $("pier-width").value,
                "fc": $("fc").value,
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
      (res.fc ? ` (crushing at f_c = ${fmt(res.fc)} MPa)` : "") +
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
      (s.sliding_governs_l || s.sliding_governs_r ? " (sliding governs)" : "") +
      (s.friction_with_crushing ? " with crushing" : "") : "";
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
  for (const id of ["pier-height", "pier-width", "friction-mu", "fc"]) {
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
  for (const id of ["record-units", "record-scale"]) $(id).addEventListener("change", reloadRecord);
  $("record-suite").addEventListener("change", listSuite);
  $("suite-record").addEventListener("change", loadSuiteRecord);
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

// ------------------------------------------------------------------ start
bindControls();
showControls();
requestStatics(performance.now());
loadSuites();
