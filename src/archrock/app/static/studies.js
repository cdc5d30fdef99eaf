// archrock app: the page's studies (the ensemble, the collapse curve, the report), each a job of
// the server polled for its progress. Loaded before app.js, whose helpers it calls.
"use strict";
// ------------------------------------------------------------------ ensemble
let polling = null;

function spreadsParams() {
  return {span: $("spread-span").value.trim(), thickness: $("spread-thickness").value.trim(),
          radius: $("spread-radius").value.trim()};
}

// a study about to run: its figure and text cleared, its old inputs forgotten; the inputs it
// is computed from, for greying it when they change
function clearResult(key, svg, out) {
  const inputs = inputsOf(key);
  $(svg).replaceChildren();
  $(out).textContent = "";
  delete shown[key];
  markStale();
  return inputs;
}

async function runEnsemble() {
  const t0 = performance.now();
  const body = {arch: archParams(), samples: $("samples").value.trim(), seed: $("seed").value.trim(),
                spreads: spreadsParams()};
  if ($("with-pulse").checked) body.pulse = pulseParams();
  if (body.pulse && friction() !== "") body.friction = friction();
  const inputs = clearResult("ensemble", "hist-svg", "ensemble-result");
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
  const inputs = clearResult("curve", "curve-svg", "curve-result");
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
                  friction: "friction-mu", button: "run-report"}};

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
  if (friction() !== "") body.friction = friction();  // the report's one friction: the page's
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
