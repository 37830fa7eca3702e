// The server's API: JSON in, JSON out; an answer with an error throws it, message intact.
// Every POST is a job (progress.js): shown with its progress and a cancel button when it
// takes more than a moment.
import {tracked} from "./progress.js";

export async function post(path, body) {
  return tracked(path, body, async (r) => {
    const data = await r.json().catch(() => ({error: `${path}: the server sent no JSON (${r.status})`}));
    if (!r.ok) throw new Error(data.error || `${path}: HTTP ${r.status}`);
    return data;
  });
}

export async function get(path) {
  const r = await fetch(path);
  const data = await r.json();
  if (!r.ok) throw new Error(data.error || `${path}: HTTP ${r.status}`);
  return data;
}

// A download of what the server makes (a file the command line writes), as a Blob.
export async function file(path, body) {
  return tracked(path, body, async (r) => {
    if (!r.ok) {
      const data = await r.json().catch(() => ({}));
      throw new Error(data.error || `${path}: HTTP ${r.status}`);
    }
    return r.blob();
  });
}

export function download(blob, name) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}
