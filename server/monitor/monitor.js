// The Vesper farm monitor: one page, no framework, nothing from the web.
//
// Live by polling, not server-sent events: the server's connection layer
// answers each request with one response and holds a handler slot
// (`[server] threads`, 16) while it does, so an event stream per open page
// would hold a slot for as long as the page is open and five pages would take
// a third of the server's capacity away from 50 workers. A poll every 2 s is
// two or three short reads (jobs, workers, and the open job), and stops while
// the tab is hidden. bench/README.md measures what five pages cost.
"use strict";

const POLL_MS = 2000;
const API = "/api/v1";
const TASK_PAGE = 500; // tasks shown on a job page
const THUMBS = 48; // thumbnails shown on a job page

const $ = (id) => document.getElementById(id);

// el("td", {class: "num"}, "text", child...): text is always text, never HTML.
function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (v === undefined || v === null || v === false) continue;
    if (k.startsWith("on")) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v === true ? "" : String(v));
  }
  for (const c of children) {
    if (c === undefined || c === null) continue;
    e.append(c instanceof Node ? c : document.createTextNode(String(c)));
  }
  return e;
}

class AuthError extends Error {}

// A call of the farm API. The session cookie goes along by itself; the
// header tells the server that the page (not a cross-site form) asks.
async function api(path, options = {}) {
  const headers = Object.assign({ "X-Vesper-Monitor": "1" }, options.headers || {});
  const response = await fetch(API + path, Object.assign({}, options, {
    headers, credentials: "same-origin", cache: "no-store",
  }));
  if (response.status === 401) throw new AuthError(await errorText(response));
  if (!response.ok) throw new Error(await errorText(response));
  const type = response.headers.get("Content-Type") || "";
  return type.startsWith("application/json") ? response.json() : response.text();
}

async function errorText(response) {
  try {
    const body = await response.json();
    return body.error || response.statusText;
  } catch (_) {
    return response.status + " " + response.statusText;
  }
}

// ---- formatting (times are the server's clock: seconds since the epoch) ----

const num = (v) => typeof v === "number" && isFinite(v);

function clock(t) {
  if (!num(t)) return "—";
  const d = new Date(t * 1000);
  const today = new Date().toDateString() === d.toDateString();
  return today ? d.toLocaleTimeString() : d.toLocaleString();
}

function span(seconds) {
  if (!num(seconds) || seconds < 0) return "—";
  const s = Math.round(seconds);
  if (s < 60) return s + " s";
  if (s < 3600) return Math.floor(s / 60) + " min " + String(s % 60).padStart(2, "0") + " s";
  return Math.floor(s / 3600) + " h " + String(Math.floor((s % 3600) / 60)).padStart(2, "0") +
    " min";
}

function stateBadge(state) {
  return el("span", { class: "state state-" + (state || "unknown") }, state || "?");
}

// Started to finished, or to now while the job runs.
function duration(item, now) {
  if (num(item.duration)) return item.duration;
  if (!num(item.started)) return undefined;
  return (num(item.finished) ? item.finished : now) - item.started;
}

function progressBar(counts, total) {
  const bar = el("div", { class: "bar", role: "progressbar", "aria-valuemin": 0,
    "aria-valuemax": total, "aria-valuenow": counts.done || 0 });
  let left = 0;
  for (const part of ["done", "failed", "leased"]) {
    const n = counts[part] || 0;
    if (!n || !total) continue;
    const s = el("span", { class: part });
    s.style.left = (100 * left / total) + "%";
    s.style.width = (100 * n / total) + "%";
    left += n;
    bar.append(s);
  }
  const pct = total ? Math.floor(100 * (counts.done || 0) / total) : 0;
  bar.append(el("b", {}, `${counts.done || 0}/${total} · ${pct} %`));
  return bar;
}

// ---- state ----

const view = {
  job: null, selectedFrame: null, histogramShown: null, workerNames: new Map(), timer: 0,
  inFlight: false,
};
let observed = []; // what the page saw change, for a reader of the DOM (the browser test)

function notice(text) {
  $("notice").hidden = !text;
  $("notice").textContent = text || "";
}

function showLogin(message) {
  document.body.dataset.view = "login";
  $("login").hidden = false;
  $("app").hidden = true;
  $("logout-button").hidden = true;
  $("login-button").hidden = true;
  $("login-error").textContent = message || "";
  $("live").textContent = "not logged in";
  $("token").focus();
}

function showApp() {
  $("login").hidden = true;
  $("app").hidden = false;
}

// ---- jobs ----

const ACTIONS = [
  ["pause", (j) => j.state === "active"],
  ["resume", (j) => j.state === "paused"],
  ["cancel", (j) => j.state === "active" || j.state === "paused"],
  ["retry-failed", (j) => (j.counts && j.counts.failed) > 0],
  ["delete", (j) => j.state !== "active"],
];

function actionButtons(job) {
  const box = el("div", { class: "actions" });
  for (const [name, applies] of ACTIONS) {
    if (!applies(job)) continue;
    box.append(el("button", {
      type: "button", class: name === "delete" || name === "cancel" ? "danger" : null,
      "data-action": name, onclick: () => act(job, name),
    }, name));
  }
  return box;
}

async function act(job, name) {
  if (name === "delete" && !window.confirm(`Delete job ${job.id} and its outputs?`)) return;
  try {
    if (name === "delete") await api(`/jobs/${job.id}`, { method: "DELETE" });
    else await api(`/jobs/${job.id}/${name}`, { method: "POST", body: "{}",
      headers: { "Content-Type": "application/json" } });
    notice("");
    if (name === "delete" && view.job === job.id) location.hash = "#/";
  } catch (e) {
    if (e instanceof AuthError) {
      // A read-only view (`monitor_read_only`): acting needs the login.
      notice(`${name}: log in with the submitter token to act on jobs`);
      $("login-button").hidden = false;
    } else {
      notice(`${name} job ${job.id}: ${e.message}`);
    }
  }
  poll();
}

function jobRow(job, now) {
  const eta = job.state === "active" && num(job.eta) ? span(job.eta) : "—";
  return el("tr", { "data-job": job.id, "data-state": job.state },
    el("td", { class: "num" }, el("a", { href: `#/jobs/${job.id}` }, job.id)),
    el("td", {}, job.name),
    el("td", {}, stateBadge(job.state)),
    el("td", {}, progressBar(job.counts || {}, job.total || 0)),
    el("td", { class: "num" }, job.priority),
    el("td", {}, clock(job.submitted)),
    el("td", {}, clock(job.started)),
    el("td", {}, clock(job.finished)),
    el("td", { class: "num" }, span(duration(job, now))),
    el("td", { class: "num" }, eta),
    el("td", {}, actionButtons(job)));
}

function renderJobs(list) {
  const now = num(list.now) ? list.now : Date.now() / 1000;
  const jobs = (list.jobs || []).slice().sort((a, b) => b.id - a.id);
  $("jobs").tBodies[0].replaceChildren(...jobs.map((j) => jobRow(j, now)));
  $("no-jobs").hidden = jobs.length > 0;
  for (const j of jobs) {
    const seen = `${j.id}:${j.state}:${(j.counts || {}).done || 0}/${j.total}`;
    if (!observed.includes(seen)) observed.push(seen);
  }
  document.body.dataset.observed = observed.join(" ");
}

// ---- one job ----

function summaryItem(label, value) {
  return el("div", {}, el("span", {}, label), value);
}

function renderJobSummary(job, now) {
  $("job-title").textContent = `Job ${job.id}: ${job.name}`;
  $("job-summary").replaceChildren(
    summaryItem("state", stateBadge(job.state)),
    summaryItem("progress", progressBar(job.counts || {}, job.total || 0)),
    summaryItem("priority", String(job.priority)),
    summaryItem("submitted", clock(job.submitted)),
    summaryItem("started", clock(job.started)),
    summaryItem("finished", clock(job.finished)),
    summaryItem("duration", span(duration(job, now))),
    summaryItem("ETA", job.state === "active" && num(job.eta) ? span(job.eta) : "—"),
    summaryItem("blocklisted workers", (job.blocked_workers || []).join(", ") || "none"));
  $("job-actions").replaceChildren(actionButtons(job));
}

function taskRow(job, t, now) {
  const samples = t.sample_end > t.sample_begin ? `${t.sample_begin}–${t.sample_end}` : "all";
  const state = t.state === "leased" && num(t.progress)
    ? el("span", {}, stateBadge(t.state), ` ${Math.round(100 * t.progress)} %`)
    : stateBadge(t.state);
  const log = t.has_log
    ? el("button", { type: "button", onclick: () => showLog(job.id, t.id) }, "log")
    : el("span", { class: "quiet" }, t.reused_from ? `reused from ${t.reused_from}` : "—");
  return el("tr", { "data-task": t.id },
    el("td", { class: "num" }, t.id), el("td", { class: "num" }, t.frame),
    el("td", {}, samples), el("td", {}, state),
    el("td", { title: t.worker || "" }, view.workerNames.get(t.worker) || t.worker || "—"),
    el("td", { class: "num" }, t.attempts), el("td", { class: "num" }, span(duration(t, now))),
    el("td", {}, log));
}

async function showLog(job, task) {
  const pre = $("log");
  pre.hidden = false;
  pre.textContent = `task ${task}: loading…`;
  try {
    const text = await api(`/jobs/${job}/tasks/${task}/log`);
    pre.textContent = `task ${task} log:\n` + (text || "(empty)");
  } catch (e) {
    pre.textContent = `task ${task}: ${e.message}`;
  }
}

function frameTile(job, f) {
  const tile = el("div", { class: "frame" + (view.selectedFrame === f.frame ? " selected" : ""),
    "data-frame": f.frame, title: f.error || "",
    onclick: () => { location.hash = `#/jobs/${job}/frames/${f.frame}`; } });
  if (f.state === "ready" && f.blob) {
    // The blob names the picture, so a finished frame's image is fetched once.
    tile.append(el("img", { alt: `frame ${f.frame}`, loading: "lazy",
      src: `${API}/jobs/${job}/frames/${f.frame}/thumbnail?blob=${f.blob.slice(0, 16)}` }));
  }
  tile.append(el("div", {}, `frame ${f.frame} `, stateBadge(f.state)));
  return tile;
}

function renderFrames(job, frames) {
  const box = $("frames");
  const shown = frames.slice(0, THUMBS);
  // Rebuilt only when a frame changed, so pictures do not flicker.
  const key = shown.map((f) => `${f.frame}:${f.state}:${f.blob || ""}`).join(",") +
    `|${view.selectedFrame}`;
  if (box.dataset.key === key) return;
  box.dataset.key = key;
  box.replaceChildren(...shown.map((f) => frameTile(job, f)));
  if (frames.length > shown.length)
    box.append(el("p", { class: "quiet" }, `… and ${frames.length - shown.length} more frames`));
  if (!frames.length) box.append(el("p", { class: "quiet" }, "No frames listed."));
}

async function renderJob(id) {
  const detail = await api(`/jobs/${id}?tasks_limit=${TASK_PAGE}`);
  const now = Date.now() / 1000;
  renderJobSummary(detail, now);
  renderFrames(id, detail.frames || []);
  await showHistogram(id, detail.frames || []);
  $("tasks").tBodies[0].replaceChildren(...(detail.tasks || []).map((t) => taskRow(detail, t, now)));
  $("tasks-more").hidden = !num(detail.tasks_next);
  $("tasks-more").textContent = `The first ${TASK_PAGE} tasks are shown ` +
    `(vesper status ${id} lists them all).`;
}

// ---- histogram ----

// The selected frame's histogram, fetched once it is ready (and once only).
async function showHistogram(job, frames) {
  const f = frames.find((x) => x.frame === view.selectedFrame);
  const key = f && f.state === "ready" ? `${job}/${f.frame}/${f.blob}` : null;
  if (!key || view.histogramShown === key) return;
  view.histogramShown = key;
  try {
    const h = await api(`/jobs/${job}/frames/${f.frame}/histogram`);
    drawHistogram(h, `Frame ${f.frame}: luminosity (${h.width}×${h.height}, sRGB, no grade)`);
  } catch (e) {
    notice(`histogram of frame ${f.frame}: ${e.message}`);
  }
}

// Bars as fractions of the pixels, scaled to the largest interior bin (a
// black background in bin 0 would flatten the rest), as the PNG plot does.
function drawHistogram(h, title) {
  $("histogram-panel").hidden = false;
  $("histogram-title").textContent = title;
  const canvas = $("histogram"), g = canvas.getContext("2d");
  const W = canvas.width, H = canvas.height, n = h.bins.length, total = h.count || 1;
  const f = h.bins.map((b) => b / total);
  let top = Math.max(...f.slice(1, n - 1));
  if (!(top > 0)) top = Math.max(...f);
  top = (top || 1) * 1.05;
  g.fillStyle = "#101114";
  g.fillRect(0, 0, W, H);
  g.fillStyle = "#2a2d35";
  for (let q = 1; q < 4; ++q) g.fillRect(Math.round(W * q / 4), 0, 1, H - 12);
  for (let i = 0; i < n; ++i) {
    const bh = Math.min(1, f[i] / top) * (H - 16);
    g.fillStyle = f[i] > top ? "#eb825a" : "#b9b9c0";
    g.fillRect(i * W / n, H - 12 - bh, Math.ceil(W / n), bh);
  }
  for (let x = 0; x < W; ++x) { // the grey each position stands for
    const v = Math.round(255 * x / (W - 1));
    g.fillStyle = `rgb(${v},${v},${v})`;
    g.fillRect(x, H - 10, 1, 10);
  }
  g.fillStyle = "#ffc83c";
  g.fillRect(Math.round(h.median * (W - 1)), 0, 2, H - 12);
  const pct = (x) => (100 * x).toFixed(1) + " %";
  $("histogram-stats").textContent = `median ${h.median.toFixed(3)} · mean ${h.mean.toFixed(3)}` +
    ` · clipped ${pct(h.clipped.low)} black, ${pct(h.clipped.high)} white · ${h.count} pixels`;
  canvas.dataset.count = h.count;
}

// ---- workers ----

function workerRow(w, now) {
  const state = w.state || (now - w.last_seen < 120 ? "online" : "offline");
  const task = w.current_task
    ? el("a", { href: `#/jobs/${w.current_task.job}` },
      `job ${w.current_task.job} task ${w.current_task.task}`)
    : "—";
  const seen = num(w.last_seen) ? `${span(now - w.last_seen)} ago` : "—";
  return el("tr", { "data-worker": w.worker_id },
    el("td", { title: w.worker_id }, w.name),
    el("td", {}, stateBadge(state)),
    el("td", { title: clock(w.last_seen) }, seen),
    el("td", {}, task),
    el("td", {}, (w.blocklisted_for || []).map((j) => `job ${j}`).join(", ") || "—"),
    el("td", { class: "num" }, w.leases));
}

function renderWorkers(list) {
  const now = num(list.now) ? list.now : Date.now() / 1000;
  const workers = list.workers || [];
  view.workerNames = new Map(workers.map((w) => [w.worker_id, w.name]));
  $("workers").tBodies[0].replaceChildren(...workers.map((w) => workerRow(w, now)));
  $("no-workers").hidden = workers.length > 0;
}

// ---- the loop ----

// #/ (jobs), #/jobs/ID (a job), #/jobs/ID/frames/N (a job, frame N's histogram).
function route() {
  const m = /^#\/jobs\/(\d+)(?:\/frames\/(-?\d+))?$/.exec(location.hash);
  const job = m ? Number(m[1]) : null;
  const frame = m && m[2] !== undefined ? Number(m[2]) : null;
  if (job !== view.job || frame !== view.selectedFrame) {
    $("histogram-panel").hidden = true;
    $("frames").dataset.key = "";
    view.histogramShown = null;
  }
  if (job !== view.job) $("log").hidden = true;
  view.job = job;
  view.selectedFrame = frame;
  $("job-view").hidden = job === null;
  $("jobs-view").hidden = job !== null;
}

async function poll() {
  clearTimeout(view.timer);
  if (view.inFlight) return;
  view.inFlight = true;
  try {
    const [jobs, workers] = await Promise.all([api("/jobs"), api("/workers")]);
    showApp();
    renderJobs(jobs);
    renderWorkers(workers);
    if (view.job !== null) await renderJob(view.job);
    document.body.dataset.view = view.job === null ? "jobs" : "job";
    document.body.dataset.polls = String(Number(document.body.dataset.polls || 0) + 1);
    $("live").textContent = `live · updated ${new Date().toLocaleTimeString()}`;
    $("live").classList.remove("stale");
    $("logout-button").hidden = false;
  } catch (e) {
    if (e instanceof AuthError) {
      view.inFlight = false;
      showLogin();
      return; // no polling until logged in
    }
    $("live").textContent = `not updated: ${e.message}`;
    $("live").classList.add("stale");
  }
  view.inFlight = false;
  if (!document.hidden) view.timer = setTimeout(poll, POLL_MS);
}

async function login(event) {
  event.preventDefault();
  try {
    await api("/login", { method: "POST", headers: { "Content-Type": "application/json" },
      body: JSON.stringify({ token: $("token").value.trim() }) });
    $("token").value = "";
    $("login-error").textContent = "";
    poll();
  } catch (e) {
    $("login-error").textContent = e.message;
  }
}

async function logout() {
  try {
    await api("/logout", { method: "POST", body: "{}",
      headers: { "Content-Type": "application/json" } });
  } catch (_) { /* the cookie is gone either way */ }
  location.reload();
}

document.addEventListener("DOMContentLoaded", () => {
  $("login-form").addEventListener("submit", login);
  $("logout-button").addEventListener("click", logout);
  $("login-button").addEventListener("click", () => showLogin());
  window.addEventListener("hashchange", () => { route(); poll(); });
  document.addEventListener("visibilitychange", () => { if (!document.hidden) poll(); });
  route();
  poll();
});
