/* Scene page: the buffer switch (buttons and keys 1-7), the three panels, and the swap view
   (a slider, or the mouse, moves the split between the real-time and the reference render). */
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("buffers").textContent);
  var buttons = document.querySelectorAll(".seg button[data-buffer]");
  var note = document.getElementById("buffer-note");
  var swap = document.getElementById("swap");
  var under = document.getElementById("swap-under");
  var over = document.getElementById("swap-over");
  var overBox = swap ? swap.querySelector(".over") : null;
  var split = swap ? swap.querySelector(".split") : null;
  var range = document.getElementById("swap-range");
  var follow = document.getElementById("swap-follow");
  var swapNote = document.getElementById("swap-note");

  function markUpscaled(img) {
    // Small renders shown large keep their pixels square, so single-pixel errors stay visible.
    if (img.naturalWidth > 0 && img.clientWidth > 1.5 * img.naturalWidth)
      img.classList.add("upscaled");
    else
      img.classList.remove("upscaled");
  }
  function markAll() {
    var imgs = document.querySelectorAll(".panels img, .swap img");
    for (var i = 0; i < imgs.length; i++) markUpscaled(imgs[i]);
  }

  function showIn(container, buffer, fallback) {
    var items = container.querySelectorAll("[data-buffer]");
    var has = false, i;
    for (i = 0; i < items.length; i++)
      if (items[i].getAttribute("data-buffer") === buffer) has = true;
    var chosen = has ? buffer : fallback;
    for (i = 0; i < items.length; i++)
      items[i].hidden = items[i].getAttribute("data-buffer") !== chosen;
    return has;
  }

  function select(buffer) {
    if (!data.buffers[buffer]) return;
    for (var i = 0; i < buttons.length; i++)
      buttons[i].setAttribute("aria-pressed",
                              buttons[i].getAttribute("data-buffer") === buffer ? "true" : "false");
    var panels = document.querySelectorAll(".panels [data-panel]");
    var exact = true;
    for (var p = 0; p < panels.length; p++) {
      var isError = panels[p].getAttribute("data-panel") === "error";
      var has = showIn(panels[p], buffer, isError ? data.errorFallback : "");
      if (isError && !has) exact = false;
    }
    if (note) {
      note.textContent = exact ? "" :
          (data.errorFallback ? "No error map for " + buffer + "; the third panel shows " +
                                data.errorLabel + "." : "");
    }
    var pair = data.buffers[buffer];
    if (swap) {
      var both = pair.realtime && pair.raymarch;
      swap.hidden = !both;
      if (swapNote) swapNote.textContent = both ? "" : "Only one renderer wrote " + buffer + ".";
      if (both) {
        under.src = pair.raymarch;
        over.src = pair.realtime;
      }
    }
    markAll();
  }

  function setSplit(percent) {
    if (!swap) return;
    percent = Math.max(0, Math.min(100, percent));
    overBox.style.clipPath = "inset(0 " + (100 - percent) + "% 0 0)";
    split.style.left = percent + "%";
    if (range && Number(range.value) !== Math.round(percent)) range.value = Math.round(percent);
  }

  for (var b = 0; b < buttons.length; b++) {
    buttons[b].addEventListener("click", function (e) {
      select(e.currentTarget.getAttribute("data-buffer"));
    });
  }
  document.addEventListener("keydown", function (e) {
    if (e.target && (e.target.tagName === "INPUT" || e.target.tagName === "TEXTAREA")) return;
    var n = parseInt(e.key, 10);
    if (n >= 1 && n <= buttons.length) select(buttons[n - 1].getAttribute("data-buffer"));
  });
  if (swap) {
    range.addEventListener("input", function () { setSplit(Number(range.value)); });
    swap.addEventListener("mousemove", function (e) {
      if (follow && !follow.checked) return;
      var r = swap.getBoundingClientRect();
      if (r.width > 0) setSplit(100 * (e.clientX - r.left) / r.width);
    });
    setSplit(50);
  }
  var imgs = document.querySelectorAll(".panels img, .swap img");
  for (var k = 0; k < imgs.length; k++)
    imgs[k].addEventListener("load", function (e) { markUpscaled(e.currentTarget); });
  window.addEventListener("resize", markAll);
  window.addEventListener("load", markAll);
  select(data.initial);
  document.documentElement.setAttribute("data-ready", "1");
})();
