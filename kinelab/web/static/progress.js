// Requests that take a while: each POST carries an id of its own ("job"), and once it has
// taken more than a moment a panel shows it (a spinner, the seconds so far, how far the
// server's work has come when the work has steps) with a button that cancels it: the page
// stops waiting and asks the server to stop the work (/api/cancel; closing the request says
// so too).
const SHOW_AFTER = 400;      // ms before a request is shown: quick ones (a drag) never are
const POLL = 500;            // ms between questions to /api/progress
const TICK = 100;            // ms between updates of the seconds shown

const LABELS = {
  "/api/derive": () => "deriving",
  "/api/synthesize": () => "solving the synthesis task",
  "/api/export": (b) => `making the ${b.kind === "svg" ? "outlines" : b.kind} file`,
  "/api/study": () => "sweeping the linkage",
  "/api/analyze": () => "analysing",
  "/api/dynamics": (b) => b.format === "csv" ? "making the forces' table" : "computing the forces",
  "/api/configuration": () => "solving the configuration",
  "/api/drag": () => "following the drag",
  "/api/flip": () => "switching the assembly mode",
  "/api/load": () => "reading the file",
  "/api/save": () => "writing the file",
};

function jobId() {
  const bytes = crypto.getRandomValues(new Uint8Array(12));   // in any context, unlike randomUUID
  return Array.from(bytes, (b) => b.toString(16).padStart(2, "0")).join("");
}

function panel() {
  let p = document.getElementById("progress");
  if (!p) {
    p = document.createElement("div");
    p.id = "progress";
    p.setAttribute("role", "status");
    p.setAttribute("aria-live", "polite");
    document.body.append(p);
  }
  return p;
}

const seconds = (ms) => `${(ms / 1000).toFixed(1)} s`;

// Post `body` to `path` as a job; `read(response)` makes the answer (and throws its error).
// A request cancelled on the page throws an Error whose `cancelled` is true.
export async function tracked(path, body, read) {
  const job = {id: jobId(), path, label: (LABELS[path] || (() => path))(body || {}),
               start: performance.now(), controller: new AbortController(), cancelled: false};
  job.showing = setTimeout(() => show(job), SHOW_AFTER);
  try {
    const r = await fetch(path, {method: "POST", headers: {"Content-Type": "application/json"},
                                 body: JSON.stringify({...body, job: job.id}),
                                 signal: job.controller.signal});
    return await read(r);
  } catch (err) {
    if (job.cancelled) {
      const e = new Error(`${job.label}: cancelled after ${seconds(performance.now() - job.start)}`);
      e.cancelled = true;
      throw e;
    }
    throw err;
  } finally {
    hide(job);
  }
}

function show(job) {
  const row = document.createElement("div");
  row.className = "job";
  row.dataset.job = job.id;
  row.dataset.path = job.path;
  row.innerHTML = `<span class="spinner" aria-hidden="true"></span>
    <span class="what"></span> <span class="elapsed"></span>
    <progress max="1" hidden></progress> <span class="stage"></span>
    <button class="cancel" title="Stop waiting, and stop the server's work">cancel</button>`;
  row.querySelector(".what").textContent = job.label;
  row.querySelector(".cancel").onclick = () => cancel(job);
  job.row = row;
  panel().append(row);
  const tick = () => { row.querySelector(".elapsed").textContent = seconds(performance.now() - job.start); };
  tick();
  job.ticking = setInterval(tick, TICK);
  job.polling = setInterval(() => poll(job), POLL);
  poll(job);
}

// What the server says of the job: its state, and what its work last reported.
async function poll(job) {
  if (!job.row || job.cancelled) return;
  try {
    const r = await fetch("/api/progress", {method: "POST", headers: {"Content-Type": "application/json"},
                                            body: JSON.stringify({job: job.id})});
    const p = await r.json();
    if (!job.row || job.cancelled || !r.ok) return;
    const stage = job.row.querySelector(".stage"), bar = job.row.querySelector("progress");
    job.row.dataset.state = p.state;
    stage.textContent = p.state === "waiting" ? "waiting for the server (busy with other long work)"
      : p.label || "";
    if (typeof p.fraction === "number") { bar.hidden = false; bar.value = p.fraction; bar.title = `${Math.round(100 * p.fraction)} %`; }
  } catch (err) { /* the answer itself says what went wrong */ }
}

function cancel(job) {
  if (job.cancelled) return;
  job.cancelled = true;
  if (job.row) {
    job.row.dataset.state = "cancelling";
    job.row.querySelector(".stage").textContent = "cancelling…";
    job.row.querySelector(".cancel").disabled = true;
  }
  job.controller.abort();
  fetch("/api/cancel", {method: "POST", headers: {"Content-Type": "application/json"},
                        body: JSON.stringify({job: job.id})}).catch(() => {});
}

function hide(job) {
  clearTimeout(job.showing);
  clearInterval(job.ticking);
  clearInterval(job.polling);
  if (job.row) job.row.remove();
  job.row = null;
}

// The jobs shown now (for the page's own use and its tests).
export function shown() {
  return [...panel().querySelectorAll(".job")].map((r) => ({job: r.dataset.job, path: r.dataset.path}));
}
