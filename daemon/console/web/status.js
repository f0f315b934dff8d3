// The radfarm status page: reads GET /api/session, then follows GET /api/events (server-sent
// events, each a whole status snapshot) and redraws the tables in place. Text goes in through
// textContent only, so a job or agent name cannot inject markup.
//
// Signing in trades the web token for a session that lives in sessionStorage, which only this
// origin (scheme, host and port) can read, and goes out in an Authorization header, never in a
// cookie that the browser would also hand to other ports of this host. EventSource cannot send
// headers, so the event stream is read with fetch().
"use strict";

const kSessionKey = "radfarm.session";
let session = { read: false, act: false, token: false, authenticated: false };
let stream = null;  // the AbortController of the event stream being read
let retryMs = 2000;  // before following the stream again once it ends
const previews = new Map();  // job id -> {key, at}: what its preview shows, and since when

function el(tag, attrs, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function seconds(s) {
  if (s === null || s === undefined) return "?";
  if (s < 60) return s.toFixed(s < 10 ? 1 : 0) + " s";
  if (s < 3600) return Math.floor(s / 60) + " min " + Math.round(s % 60) + " s";
  return Math.floor(s / 3600) + " h " + Math.round((s % 3600) / 60) + " min";
}

function rate(r) {
  if (!r) return "0";
  if (r >= 1e6) return (r / 1e6).toFixed(2) + " M";
  if (r >= 1e3) return (r / 1e3).toFixed(1) + " k";
  return r.toFixed(0);
}

// The row of `key` in `tbody`, made with `cells` empty cells if missing; rows not in `keep` go.
function rowFor(tbody, key, cells) {
  let row = tbody.querySelector(`tr[data-key="${CSS.escape(String(key))}"]`);
  if (!row) {
    row = el("tr", { "data-key": String(key) });
    for (let i = 0; i < cells; i++) row.appendChild(el("td"));
    tbody.appendChild(row);
  }
  return row;
}

function prune(tbody, keep) {
  for (const row of Array.from(tbody.rows)) {
    if (!keep.has(row.dataset.key)) row.remove();
  }
}

function setText(cell, text, cls) {
  if (cell.textContent !== text) cell.textContent = text;
  if (cls !== undefined) cell.className = cls;
}

// The headers that carry this tab's session, if it signed in.
function auth(extra) {
  const headers = Object.assign({ "X-Radfarm-Request": "1" }, extra || {});
  const s = sessionStorage.getItem(kSessionKey);
  if (s) headers.Authorization = `Bearer ${s}`;
  return headers;
}

// fetch() with this tab's session; a session the master no longer knows (expired, signed out, the
// master restarted) is forgotten and the page starts again signed out.
async function authFetch(url, options) {
  const r = await fetch(url, Object.assign({}, options, { headers: auth((options || {}).headers),
                                                          credentials: "omit" }));
  if (r.status === 401 && sessionStorage.getItem(kSessionKey)) {
    sessionStorage.removeItem(kSessionKey);
    setTimeout(loadSession, 0);
  }
  return r;
}

function act(id, action) {
  authFetch(`/api/jobs/${id}/${action}`, { method: "POST" }).then(async (r) => {
    if (!r.ok) {
      const body = await r.json().catch(() => ({}));
      alert(`${action} job ${id}: ${body.error || r.status}`);
    }
  });
}

function drawActions(cell, job) {
  const wanted = [];
  if (session.act) {
    // A held job (a store fault) resumes by itself; pause makes it wait for the operator.
    if (["running", "queued", "held"].includes(job.state)) wanted.push("pause");
    if (["paused", "held"].includes(job.state)) wanted.push("resume");
    if (["running", "queued", "paused", "held"].includes(job.state)) wanted.push("cancel");
  }
  const have = Array.from(cell.querySelectorAll("button")).map((b) => b.dataset.action);
  if (have.join() === wanted.join()) return;
  cell.replaceChildren();
  for (const action of wanted) {
    const b = el("button", { "data-action": action, type: "button" }, action);
    b.addEventListener("click", () => act(job.id, action));
    cell.appendChild(b);
  }
}

function drawPreview(cell, job) {
  if (job.round === 0 && job.state !== "done") {
    cell.replaceChildren();
    return;
  }
  // A new image when the job moved on, at most every 5 s (rendering one meshes the scene), and
  // once more when it ends.
  const seen = previews.get(job.id);
  const now = Date.now();
  const finished = ["done", "failed", "cancelled"].includes(job.state);
  const key = `${job.round}/${finished}`;
  if (seen && (seen.key === key || (!finished && now - seen.at < 5000))) return;
  previews.set(job.id, { key, at: now });
  let img = cell.querySelector("img");
  let link = cell.querySelector("a");
  if (!img) {
    // A link to the whole image (kPreviewPixels on its longer side) in a tab of its own.
    link = el("a", { class: "preview-link", target: "_blank", rel: "noopener",
                     title: `job ${job.id}: the whole preview` });
    img = el("img", { class: "preview", alt: `job ${job.id}` });
    img.addEventListener("error", () => { img.hidden = true; });
    img.addEventListener("load", () => { img.hidden = false; });
    link.appendChild(img);
    cell.appendChild(link);
  }
  // Fetched with the session's header (an <img> cannot send one), shown from a blob: URL.
  authFetch(`/api/jobs/${job.id}/preview.png?v=${encodeURIComponent(key)}`)
    .then((r) => (r.ok ? r.blob() : Promise.reject(r.status)))
    .then((blob) => {
      if (img.src.startsWith("blob:")) URL.revokeObjectURL(img.src);
      img.src = URL.createObjectURL(blob);
      link.href = img.src;
    })
    .catch(() => { img.hidden = true; });
}

// Where a job's time went: each phase's wall seconds (the longest place's), one line each, and
// every place's CPU seconds in the cell's title.
function drawTimeline(cell, job) {
  const phases = new Map();
  for (const e of job.timeline || []) {
    const p = phases.get(e.phase) || { wall: 0, cpu: [] };
    p.wall = Math.max(p.wall, e.wall_seconds);
    p.cpu.push(`${e.where} ${seconds(e.cpu_seconds)}`);
    phases.set(e.phase, p);
  }
  const lines = [], titles = [];
  for (const [phase, p] of phases) {
    lines.push(`${phase} ${seconds(p.wall)}`);
    titles.push(`${phase}: ${seconds(p.wall)}, CPU ${p.cpu.join(", ")}`);
  }
  setText(cell, lines.join("\n"), "timeline");
  if (cell.title !== titles.join("\n")) cell.title = titles.join("\n");
}

function drawJobs(jobs) {
  const tbody = document.querySelector("#jobs tbody");
  const keep = new Set();
  for (const job of jobs) {
    keep.add(String(job.id));
    const row = rowFor(tbody, job.id, 11);
    row.className = `job state-${job.state}`;
    row.dataset.state = job.state;
    row.dataset.progress = String(job.progress);
    const c = row.cells;
    setText(c[0], String(job.id), "number");
    setText(c[1], job.name);
    setText(c[2], job.state, "state");
    if (!c[3].firstChild) {
      const bar = el("span", { class: "bar" });
      bar.appendChild(el("div"));
      c[3].append(bar, el("span", { class: "percent" }));
    }
    const percent = (100 * job.progress).toFixed(1) + "%";
    c[3].querySelector(".bar > div").style.width = percent;
    setText(c[3].querySelector(".percent"), " " + percent);
    setText(c[4], String(job.round), "number");
    setText(c[5], job.state === "running" ? seconds(job.eta_seconds) : "", "number eta");
    setText(c[6], job.state === "running" ? rate(job.rays_per_second) : "", "number rate");
    setText(c[7], String(job.agents), "number");
    drawTimeline(c[8], job);
    drawPreview(c[9], job);
    drawActions(c[10], job);
  }
  prune(tbody, keep);
  document.getElementById("no-jobs").hidden = jobs.length > 0;
}

function drawAgents(agents) {
  const tbody = document.querySelector("#agents tbody");
  const keep = new Set();
  for (const a of agents) {
    keep.add(String(a.id));
    const row = rowFor(tbody, a.id, 7);
    const state = a.stale ? "stale" : a.leases > 0 ? "busy" : "idle";
    row.className = `agent agent-${state}`;
    row.dataset.name = a.name;
    row.dataset.state = state;
    const host = a.address.replace(/:\d+$/, "").replace(/^\[(.*)\]$/, "$1");
    const c = row.cells;
    setText(c[0], a.name, "name");
    setText(c[1], host);
    setText(c[2], String(a.threads), "number");
    setText(c[3], rate(a.rays_per_second), "number");
    setText(c[4], state, "state");
    setText(c[5], String(a.leases), "number");
    setText(c[6], seconds(a.last_heartbeat_ms_ago / 1000) + " ago", "number");
  }
  prune(tbody, keep);
  document.getElementById("no-agents").hidden = agents.length > 0;
}

function drawEvents(events) {
  const list = document.getElementById("events");
  const items = events.map((e) => {
    const when = new Date(e.time_ms).toLocaleTimeString();
    const who = e.job === null || e.job === undefined ? "farm" : `job ${e.job}`;
    return el("li", { class: `level-${e.level}` }, `${when} ${e.level} ${who}: ${e.text}`);
  });
  list.replaceChildren(...items);
}

function draw(status) {
  // Until the first snapshot the page says it is loading, never that there is nothing.
  for (const id of ["loading-jobs", "loading-agents", "loading-events"]) {
    document.getElementById(id).hidden = true;
  }
  drawJobs(status.jobs);
  drawAgents(status.agents);
  drawEvents(status.events);
  document.getElementById("updated").textContent =
    "updated " + new Date(status.time_ms).toLocaleTimeString();
}

function setConnection(state) {
  const c = document.getElementById("connection");
  c.dataset.state = state;
  c.textContent = state;
}

// One server-sent event ("event: status\ndata: {...}"); comments and retry: lines are skipped.
// "evicted" comes last on a stream a newer tab took the place of: it says when to come back.
function onEvent(block) {
  let type = "message";
  const data = [];
  for (const line of block.split("\n")) {
    if (line.startsWith("event: ")) type = line.slice(7);
    else if (line.startsWith("data: ")) data.push(line.slice(6));
  }
  if (type === "status" && data.length > 0) draw(JSON.parse(data.join("\n")));
  if (type === "evicted" && data.length > 0) retryMs = JSON.parse(data.join("\n")).retry_ms;
}

// Reads GET /api/events until it ends, then tries again 2 s later (as EventSource would), or as
// much later as an "evicted" event asked.
async function follow() {
  if (stream) stream.abort();
  const mine = new AbortController();
  stream = mine;
  retryMs = 2000;
  try {
    const r = await authFetch("/api/events", { signal: mine.signal });
    if (!r.ok || !r.body) throw new Error(`HTTP ${r.status}`);
    setConnection("live");
    const reader = r.body.pipeThrough(new TextDecoderStream()).getReader();
    let buffer = "";
    for (;;) {
      const { value, done } = await reader.read();
      if (done) break;
      buffer += value;
      let end;
      while ((end = buffer.indexOf("\n\n")) >= 0) {
        onEvent(buffer.slice(0, end));
        buffer = buffer.slice(end + 2);
      }
    }
  } catch (e) {
    if (mine.signal.aborted) return;  // a newer follow() took over
  }
  if (stream !== mine) return;
  setConnection(retryMs > 2000 ? "too many open pages: reconnecting later" : "reconnecting");
  setTimeout(() => { if (stream === mine) follow(); }, retryMs);
}

async function loadSession() {
  const r = await authFetch("/api/session");
  if (!r.ok) return;  // a refused session: authFetch starts again signed out
  session = await r.json();
  document.getElementById("login").hidden = !session.token || session.authenticated;
  document.getElementById("logout").hidden = !session.authenticated;
  document.getElementById("session").textContent =
    session.act ? "signed in: actions enabled"
    : session.token ? "read-only until you sign in"
    : "read-only (no web token configured)";
  if (session.read) follow();
  else {
    if (stream) stream.abort();
    stream = null;
    setConnection("sign in to see the farm");
  }
}

document.getElementById("login").addEventListener("submit", async (e) => {
  e.preventDefault();
  const token = document.getElementById("token").value;
  const r = await fetch("/api/session", {
    method: "POST",
    headers: { "X-Radfarm-Request": "1", "Content-Type": "application/json" },
    credentials: "omit",
    body: JSON.stringify({ token }),
  });
  const body = await r.json().catch(() => ({}));
  if (!r.ok || !body.session) {
    alert(`sign in: ${body.error || r.status}`);
    return;
  }
  sessionStorage.setItem(kSessionKey, body.session);
  document.getElementById("token").value = "";
  await loadSession();
});

// Signing out ends the session on the master too, so a copy of it is worth nothing.
document.getElementById("logout").addEventListener("click", async () => {
  await authFetch("/api/session", { method: "DELETE" }).catch(() => {});
  sessionStorage.removeItem(kSessionKey);
  await loadSession();
});

loadSession();
