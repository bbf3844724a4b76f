// whitted serve: the attempt page follows its attempt without reloading until it is done
// (queue position, then the run: for a project, the case it is running), then reloads once
// to show the result. No inline script: the page's Content-Security-Policy allows this file
// only.
"use strict";
(function () {
  const body = document.body;
  const url = body.dataset.status;
  const state = document.getElementById("state");
  if (!url || !state) return;
  function step(s) {
    const p = s.step;
    if (p && p.step === "compiling") return "compiling your files";
    if (p && p.step === "running") return "running case " + p.index + " of " + p.of + ": " + p.case;
    if (p && p.step === "checking") return "checking case " + p.index + " of " + p.of + ": " + p.case;
    if (s.job && s.job.state === "PENDING") return "waiting for a machine of the farm (Slurm job " + s.job.id + ")";
    if (s.job) return "starting on the farm (Slurm job " + s.job.id + ")";
    return s.what;
  }
  function say(s) {
    if (s.status === "queued") {
      state.textContent = s.position === 0
        ? "Queued: next to run."
        : "Queued: " + s.position + " before it.";
    } else if (s.status === "running") {
      state.textContent = "Running: " + step(s) + " (for " + s.seconds + " s).";
    }
  }
  function poll() {
    fetch(url, { credentials: "same-origin", cache: "no-store" })
      .then(function (r) { return r.json(); })
      .then(function (s) {
        if (s.status === "done") { window.location.reload(); return; }
        say(s);
        setTimeout(poll, 1000);
      })
      .catch(function () { setTimeout(poll, 3000); });
  }
  poll();
})();
