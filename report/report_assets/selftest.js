/* Page self-test, run first in <head>: records script errors, console.error calls, rejected
   promises and resources (images) that fail to load, then, once the page has loaded, checks
   that every <img> decoded, that every <video> loaded its metadata (its duration is shown),
   that the page is no wider than its window and no table marked data-fit (the index's) wider
   than its box (in windows 1280 px wide and wider), and that the page script ran to its end (it sets data-ready on <html>). The verdict goes into the element with id "selftest": "selftest: ok (N images)", or
   "selftest: FAIL" and one line per problem. tests/report_browser_test.cpp reads it from
   Chromium's --dump-dom; a person sees it in the footer. */
(function () {
  "use strict";
  var problems = [];
  var loaded = false;
  function show() {
    if (!loaded) return;
    var el = document.getElementById("selftest");
    if (!el) return;
    var images = document.images, good = 0;
    var lines = problems.slice();
    for (var i = 0; i < images.length; i++) {
      var im = images[i];
      if (im.complete && im.naturalWidth > 0) good++;
      else lines.push("image did not load: " + im.getAttribute("src"));
    }
    // Videos (a sequence's): each must have loaded its metadata, and says its duration.
    var videos = document.getElementsByTagName("video"), durations = [];
    for (var v = 0; v < videos.length; v++) {
      var vid = videos[v];
      if (vid.readyState >= 1 && isFinite(vid.duration) && vid.duration > 0)
        durations.push(vid.duration.toFixed(3) + " s");
      else
        lines.push("video did not load: " + (vid.currentSrc || vid.getAttribute("id") || "video"));
    }
    // The page fits its window, in the widths the report is laid out for (1280 px and more):
    // nothing wider than the page, and no table marked data-fit (the index's) wider than its
    // box.
    var root = document.documentElement;
    var laidOut = window.innerWidth >= 1280;
    if (laidOut && root.scrollWidth > root.clientWidth + 1)
      lines.push("the page overflows its window: " + root.scrollWidth + " px in " +
                 root.clientWidth + " px");
    var fits = document.querySelectorAll("[data-fit]");
    for (var f = 0; laidOut && f < fits.length; f++) {
      var box = fits[f].parentElement;
      if (fits[f].scrollWidth > box.clientWidth + 1)
        lines.push("table #" + (fits[f].id || f) + " overflows its page: " +
                   fits[f].scrollWidth + " px in " + box.clientWidth + " px");
    }
    if (!document.documentElement.hasAttribute("data-ready"))
      lines.push("the page script did not run to its end");
    el.textContent = lines.length ? "selftest: FAIL\n" + lines.join("\n")
                                  : "selftest: ok (" + good + " images" +
                                    (durations.length ? "; videos: " + durations.join(", ") : "") + ")";
    el.setAttribute("data-status", lines.length ? "fail" : "ok");
  }
  window.addEventListener("error", function (e) {
    var t = e.target;
    if (t && t !== window && t.tagName) {
      problems.push("resource failed to load: <" + t.tagName.toLowerCase() + "> " +
                    (t.getAttribute("src") || t.getAttribute("href") || ""));
    } else {
      problems.push("script error: " + e.message + " (" + (e.filename || "inline") + ":" +
                    (e.lineno || 0) + ")");
    }
    show();
  }, true);
  document.addEventListener("securitypolicyviolation", function (e) {
    problems.push("blocked by the offline policy: " + e.blockedURI + " (" + e.violatedDirective + ")");
    show();
  });
  window.addEventListener("unhandledrejection", function (e) {
    problems.push("unhandled promise rejection: " + e.reason);
    show();
  });
  var consoleError = console.error;
  console.error = function () {
    problems.push("console.error: " + Array.prototype.join.call(arguments, " "));
    show();
    return consoleError.apply(console, arguments);
  };
  window.addEventListener("load", function () { loaded = true; show(); });
  // Media events do not bubble: listen in the capture phase for any video's metadata.
  document.addEventListener("loadedmetadata", show, true);
})();
