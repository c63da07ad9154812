/* Index page: nothing interactive beyond links; marks the page as having run its script. */
(function () {
  "use strict";
  document.documentElement.setAttribute("data-ready", "1");
})();
