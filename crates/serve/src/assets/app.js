// whitted serve: the attempt page follows its attempt without reloading until it is done
// (queue position, then the run), then reloads once to show the result. No inline script:
// the page's Content-Security-Policy allows this file only.
"use strict";
(function () {
  const body = document.body;
  const url = body.dataset.status;
  const state = document.getElementById("state");
  if (!url || !state) return;
  function say(s) {
    if (s.status === "queued") {
      state.textContent = s.position === 0
        ? "Queued: next to run."
        : "Queued: " + s.position + " before it.";
    } else if (s.status === "running") {
      state.textContent = "Running: " + s.what + " (for " + s.seconds + " s).";
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
