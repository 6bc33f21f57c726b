// embroact studio page: sends edits to the server and shows what it answers.
// The page computes nothing itself: every picture and number comes from the server,
// which calls the same functions as the embroact command line.
"use strict";

const TOKEN = new URLSearchParams(location.search).get("token") || "";
const $ = (id) => document.getElementById(id);
const state = { chain: Promise.resolve(), shown: 0, sliderQueued: false, fieldKeys: "",
  actuators: [] };

async function api(path, body) {
  const opts = { headers: { "X-Embroact-Token": TOKEN } };
  if (body !== undefined) {
    opts.method = "POST";
    opts.headers["Content-Type"] = "application/json";
    opts.body = JSON.stringify(body);
  }
  const response = await fetch(path, opts);
  let data;
  try {
    data = await response.json();
  } catch (err) {
    data = { error: `server answered ${response.status} without JSON` };
  }
  return { ok: response.ok, status: response.status, data };
}

function setStatus(text, isError) {
  const el = $("status");
  el.textContent = text;
  el.classList.toggle("error", Boolean(isError));
}

function fmt(value, digits) {
  if (value === null || value === undefined) return "n/a";
  if (typeof value !== "number") return String(value);
  return value.toFixed(digits === undefined ? 3 : digits);
}

function fieldId(key) {
  return "f-" + key.replace(/[^A-Za-z0-9_]/g, "-");
}

function pressure() {
  return Number($("pressure").value);
}

// ------------------------------------------------------------------ the form
function buildFields(fields) {
  const form = $("fields");
  form.replaceChildren();
  const groups = new Map();
  for (const f of fields) {
    if (!groups.has(f.group)) {
      const fs = document.createElement("fieldset");
      const legend = document.createElement("legend");
      legend.textContent = f.group;
      fs.append(legend);
      form.append(fs);
      groups.set(f.group, fs);
    }
    const row = document.createElement("label");
    row.className = "field";
    const name = document.createElement("span");
    name.className = "key";
    name.textContent = f.key.split(".").pop();
    name.title = f.key;
    let input;
    if (f.kind === "choice" || f.kind === "bool") {
      input = document.createElement("select");
      for (const c of f.choices) {
        const opt = document.createElement("option");
        opt.value = opt.textContent = c;
        input.append(opt);
      }
    } else {
      input = document.createElement("input");
      input.type = "text";
      if (f.kind === "number") input.inputMode = "decimal";
      if (f.optional) input.placeholder = "from calibration";
    }
    input.id = fieldId(f.key);
    input.dataset.key = f.key;
    input.addEventListener("change", () => edit({ [f.key]: input.value }));
    const msg = document.createElement("div");
    msg.className = "msg";
    msg.id = "m-" + fieldId(f.key).slice(2);
    row.append(name, input, msg);
    groups.get(f.group).append(row);
  }
}

function fieldText(value) {
  // a field's value as shown: numbers to 6 significant digits (the design keeps every digit until a field is edited)
  if (value === null || value === undefined) return "";
  if (typeof value !== "number") return String(value);
  return String(Number(value.toPrecision(6)));
}

function showFields(fields) {
  const keys = fields.map((f) => f.key).join("|");
  if (keys !== state.fieldKeys) {
    buildFields(fields);
    state.fieldKeys = keys;
  }
  for (const f of fields) {
    const input = $(fieldId(f.key));
    if (input === document.activeElement && input.classList.contains("invalid")) continue;  // being corrected
    input.value = fieldText(f.value);
    input.classList.remove("invalid");
    $("m-" + fieldId(f.key).slice(2)).textContent = "";
  }
}

function showFieldError(key, message) {
  const input = $(fieldId(key));
  const msg = input ? $("m-" + fieldId(key).slice(2)) : null;
  if (input) input.classList.add("invalid");
  if (msg) msg.textContent = message;
  setStatus("not applied: " + message, true);
}

// ------------------------------------------------------------------ the views
function table(rows) {
  const t = document.createElement("table");
  for (const [label, value, id] of rows) {
    const tr = t.insertRow();
    tr.insertCell().textContent = label;
    const td = tr.insertCell();
    td.className = "num";
    td.textContent = value;
    if (id) td.id = id;
  }
  return t;
}

function geometryRows(d, m, id) {
  // the realised geometry and model of an actuator or of one segment (id: the ids' suffix, or null)
  const rows = [
    ["G [MPa]", m ? fmt(m.g_mpa, 4) : "no model"],
    ["P0 [kPa]", m ? fmt(m.p0_kpa, 2) : "no model", id === null ? null : `p0-${id}`],
    ["realised w [mm]", fmt(d.width_mm, 3), id === null ? null : `width-${id}`],
    ["realised s [mm]", fmt(d.interval_mm, 3)],
    ["realised alpha0 [deg]", fmt(d.angle_deg, 2)],
    ["l0 [mm]", fmt(d.length_mm, 2)],
    ["sleeve r0 [mm]", fmt(d.r0_mm, 4)],
    ["beta0 [deg]", fmt(d.beta0_deg, 3)],
    ["tube-law P0 [kPa]", m ? fmt(m.tube_law_p0_kpa, 2) : "no model"],
    ["neutral angle [deg]", fmt(d.neutral_angle_deg, 2)],
  ];
  if (m) rows.push(["G, P0 from", m.g_source === m.p0_source ? m.g_source : `${m.g_source}; ${m.p0_source}`]);
  return rows;
}

function showNumbers(v) {
  const box = $("numbers");
  box.replaceChildren();
  v.actuators.forEach((a, i) => {
    // a chain of segments; a chain of one is the actuator itself, shown as one block
    const segs = (a.segments || []).length > 1 ? a.segments : [];
    const h = document.createElement("h2");
    h.textContent = segs.length ? `${a.name} (${segs.length} segments: ${segs.map((s) => s.pattern).join(", ")})`
      : `${a.name} (${a.pattern})`;
    const rows = [
      [`bend at ${fmt(v.pressure_kpa, 0)} kPa [deg]`, fmt(a.theta_deg, 2), `angle-${i}`],
      ["state", a.note || a.status || a.model_error || "n/a", `status-${i}`],  // the note names the status
    ];
    if (!segs.length) rows.push(...geometryRows(a.derived, a.model, i));
    box.append(h, table(rows));
    segs.forEach((seg, k) => {  // a segmented actuator: its whole strip above, each segment's own numbers here
      const sh = document.createElement("h3");
      sh.textContent = `segment ${k} (${seg.pattern}), from ${fmt(seg.start_mm, 1)} mm`;
      const t = (a.segment_theta_deg || [])[k];
      box.append(sh, table([[`bend at ${fmt(v.pressure_kpa, 0)} kPa [deg]`, fmt(t, 2), `angle-${i}-${k}`],
                            ...geometryRows(seg.derived, seg.model, `${i}-${k}`)]));
    });
  });
}

function showWorksheet(ws) {
  const rows = [
    ["stitches", ws.stitch_count], ["jumps", ws.jump_count], ["trims", ws.trim_count], ["stops", ws.stop_count],
    ["top thread [m]", fmt(ws.top_thread_m, 2)], ["bobbin thread [m]", fmt(ws.bobbin_thread_m, 2)],
    ["sewing time [min]", fmt(ws.sewing_time_s / 60, 1)], ["handling time [min]", fmt(ws.handling_time_s / 60, 1)],
    ["needle area [mm]", ws.size_mm.map((x) => fmt(x, 1)).join(" x ")],
    ["fabric to cut [mm]", ws.fabric_mm.map((x) => fmt(x, 0)).join(" x ")],
  ];
  for (const a of ws.actuators) rows.push([`${a.name}: tube to cut [mm]`, fmt(a.tube_cut_mm, 0)]);
  $("worksheet").replaceChildren(table(rows));
}

function zoomStitches() {
  // the preview is drawn in mm (width="...mm"); zoom keeps its proportions and its scale bar
  const svg = document.querySelector("#stitches svg");
  if (!svg) return;
  const zoom = $("zoom").value;
  if (!svg.dataset.widthMm) svg.dataset.widthMm = String(parseFloat(svg.getAttribute("width")));
  svg.classList.toggle("fit", zoom === "fit");
  svg.style.width = zoom === "fit" ? "" : `${Number(svg.dataset.widthMm) * Number(zoom)}mm`;
  svg.style.height = zoom === "fit" ? "" : "auto";
}

function highlight(k) {
  for (const el of document.querySelectorAll("#finding-list li, circle.finding")) {
    el.classList.toggle("active", el.dataset.finding === String(k));
  }
  const mark = document.querySelector(`circle.finding[data-finding="${k}"]`);
  if (mark) mark.scrollIntoView({ block: "nearest", inline: "nearest" });
}

function showFindings(v) {
  $("summary").textContent = v.summary;
  const list = $("finding-list");
  list.replaceChildren();
  v.findings.forEach((f, k) => {
    const li = document.createElement("li");
    li.dataset.finding = String(k);
    const sev = document.createElement("span");
    sev.className = "sev-" + f.severity;
    sev.textContent = `${f.code} ${f.severity}`;
    const place = [f.actuator, f.stitch_index !== null ? `stitch ${f.stitch_index}` : null,
      f.xy_mm ? `(${fmt(f.xy_mm[0], 1)}, ${fmt(f.xy_mm[1], 1)}) mm` : null].filter(Boolean).join(", ");
    li.append(sev, ` ${f.message}` + (place ? ` [${place}]` : "") + (f.fix ? ` Fix: ${f.fix}` : ""));
    li.addEventListener("click", () => highlight(k));
    list.append(li);
  });
  if (!v.findings.length) list.textContent = "no findings";
}

function showViews(v) {
  $("design-name").textContent = v.design;
  $("out-dir").textContent = "into " + v.out_dir;
  const slider = $("pressure");
  slider.max = String(v.max_pressure_kpa);
  if (Number(slider.value) !== v.pressure_kpa) slider.value = String(v.pressure_kpa);
  $("pressure-value").textContent = fmt(v.pressure_kpa, 0);
  showFields(v.fields);
  $("stitches").innerHTML = v.stitches_svg;
  zoomStitches();
  $("chart").innerHTML = v.chart_svg;
  $("side").innerHTML = v.side_svg;
  showNumbers(v);
  showFindings(v);
  showWorksheet(v.worksheet);
  state.actuators = v.actuators.map((a) => a.name);
  const sel = $("inv-actuator");
  if (sel.options.length !== state.actuators.length) {
    sel.replaceChildren(...state.actuators.map((n, i) => new Option(n, String(i))));
  }
  const kinds = $("inv-pattern");  // the registered kinds inverse design searches, as the server lists them
  if ([...kinds.options].map((o) => o.value).join("|") !== v.inverse_patterns.join("|")) {
    const chosen = kinds.value;
    kinds.replaceChildren(...v.inverse_patterns.map((n) => new Option(n, n)));
    if (v.inverse_patterns.includes(chosen)) kinds.value = chosen;
  }
  if (!$("save-name").value) $("save-name").value = `${v.design}.toml`;
}

// ------------------------------------------------------------------ requests
// Requests run one after the other (an edit is never overtaken by an older view), and
// slider moves made while one is waiting are folded into it.
function enqueue(request) {
  const done = state.chain.then(() => show(request));
  state.chain = done.catch((err) => setStatus(String(err), true));
  return done;
}

async function show(request) {
  setStatus("computing...");
  const res = await request();
  if (!res.ok || res.data.applied === false) {
    if (res.data.key) showFieldError(res.data.key, res.data.error);
    else setStatus(res.data.error, true);
    return res;
  }
  showViews(res.data);
  const shape = await api(`api/shape3d?pressure_kpa=${res.data.pressure_kpa}`);
  if (shape.ok) $("shape3d").innerHTML = shape.data.svg;
  else setStatus(shape.data.error, true);
  state.shown += 1;
  document.body.dataset.version = String(state.shown);
  setStatus(res.data.summary);
  return res;
}

function slide() {
  $("pressure-value").textContent = $("pressure").value;
  if (state.sliderQueued) return;
  state.sliderQueued = true;
  enqueue(() => {
    state.sliderQueued = false;
    return api(`api/views?pressure_kpa=${pressure()}`);
  });
}

function edit(values) {
  return enqueue(() => api("api/edit", { values, pressure_kpa: pressure() }));
}

function resultText(id, text, isError) {
  const el = $(id);
  el.textContent = text;
  el.classList.toggle("error", Boolean(isError));
}

async function save() {
  const res = await api("api/save", { name: $("save-name").value });
  resultText("output-result", res.ok ? `saved ${res.data.file} in ${res.data.out_dir}` : res.data.error, !res.ok);
}

async function build() {
  resultText("output-result", "building...");
  const res = await api("api/build", { force: $("force").checked });
  resultText("output-result", res.ok ? `wrote ${res.data.files.length} files to ${res.data.out_dir}: ` +
    res.data.files.join(", ") : res.data.error, !res.ok);
}

async function inverse() {
  resultText("inv-result", "searching...");
  $("inv-apply").hidden = true;
  $("shape-apply").hidden = true;  // one proposal at a time: this search replaces the shape's
  const res = await api("api/inverse", {
    bend_deg: $("inv-bend").value, pressure_kpa: $("inv-pressure").value,
    pattern: $("inv-pattern").value, actuator: Number($("inv-actuator").value || 0),
  });
  if (!res.ok) {
    resultText("inv-result", res.data.error, true);
    return;
  }
  const b = res.data.best;
  const params = Object.entries(b.params).map(([k, x]) => `${k} ${fmt(x, 3)}`).join(", ");
  const steps = b.sensitivity.map((s) => {
    const step = s.step_mm !== undefined ? `${fmt(s.step_mm, 3)} mm` : `${fmt(s.step_deg, 3)} deg`;
    return `${s.parameter} -${step}: ${fmt(s.minus_step_theta_change_deg, 2)} deg, +${step}: ` +
      `${fmt(s.plus_step_theta_change_deg, 2)} deg`;
  }).join("; ");
  const exact = b.exact_pressure_kpa === null ? "" : `; bends by the target at ${fmt(b.exact_pressure_kpa, 1)} kPa`;
  const band = b.theta_sd_deg === null ? "no 1-sigma band claimed" : `1-sigma band +-${fmt(b.theta_sd_deg, 2)} deg`;
  resultText("inv-result", `${res.data.statement}\n${res.data.reached ? "best" : "nearest"}: ${b.pattern}, ` +
    `${params}: ${fmt(b.theta_deg, 2)} deg sewn${exact}; limit ${b.limit}; ${band}\n` +
    `one machine-grid step (sewn again, G, P0 and geometry following): ${steps}\n` +
    `findings: ${b.findings.length ? b.findings.join("; ") : "none"}`, !res.data.reached);
  $("inv-apply").hidden = !res.data.reached;  // offered only for a design that bends as wanted
}

async function inverseShape() {
  resultText("shape-result", "searching...");
  $("shape-fit").innerHTML = "";
  $("shape-apply").hidden = true;
  $("inv-apply").hidden = true;  // one proposal at a time: this search replaces the bend's
  const res = await api("api/inverse-shape", {
    path_d: $("shape-d").value, pressure_kpa: $("shape-pressure").value,
    max_segments: Number($("shape-segments").value), actuator: Number($("inv-actuator").value || 0),
  });
  if (!res.ok) {
    resultText("shape-result", res.data.error, true);
    return;
  }
  const segs = res.data.segments.map((s, k) => `segment ${k}: ${s.pattern} ` +
    Object.entries(s.params).map(([p, x]) => `${p} ${fmt(x, 3)}`).join(", ") + `, length_mm ${fmt(s.length_mm, 2)}`);
  resultText("shape-result", `${res.data.statement}\nRMSE ${fmt(res.data.rmse_mm, 3)} mm, tip ` +
    `${fmt(res.data.tip_error_mm, 2)} mm off\n${segs.join("\n")}`, !res.data.reached);
  $("shape-fit").innerHTML = res.data.svg;  // the predicted shape drawn over the target
  $("shape-apply").hidden = !res.data.reached;  // offered only for a reachable shape
}

function start() {
  $("pressure").addEventListener("input", slide);
  $("zoom").addEventListener("change", zoomStitches);
  $("fields").addEventListener("submit", (ev) => ev.preventDefault());
  $("save").addEventListener("click", save);
  $("build").addEventListener("click", build);
  $("inv-run").addEventListener("click", inverse);
  $("inv-apply").addEventListener("click", () => {  // the proposal: the pattern, and a start with the rails on the grid
    $("inv-apply").hidden = true;
    enqueue(() => api("api/apply-proposal", { pressure_kpa: pressure() }));
  });
  $("shape-run").addEventListener("click", inverseShape);
  $("shape-apply").addEventListener("click", () => {
    $("shape-apply").hidden = true;
    enqueue(() => api("api/apply-proposal", { pressure_kpa: pressure() }));
  });
  enqueue(() => api("api/views")).then(() => { document.body.dataset.ready = "1"; });
}

start();
