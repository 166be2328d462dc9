/* Draw a GlowScript canvas only when something on it changed: see export/idle_render.py. */
(function () {
  if (window.__drawWhenChanged) return;
  window.__drawWhenChanged = true;
  var RENDER = 0;          /* GlowScript 3.2's WebGLRenderer mode for a frame on the screen */
  var QUIET_MS = 5000;     /* a frame at least this often all the same */
  function changed(c) {
    var key;
    for (key in c.__changed) return true;
    for (key in (c.__vertex_changed || {})) return true;
    if (c.waitfor_textures || (c.__overlay_objects && c.__overlay_objects.__changed)) return true;
    if (!c.__last_center || !c.__last_axis || !c.__last_up) return true;
    if (!c.__center.equals(c.__last_center) || !c.__axis.equals(c.__last_axis) || !c.__up.equals(c.__last_up)) return true;
    return c.__width !== c.__last_width || c.__height !== c.__last_height || c.__range !== c.__last_range;
  }
  function drawWhenChanged(c) {
    var renderer = c && c.__renderer;
    if (!renderer || renderer.__drawsWhenChanged) return;
    var render = renderer.render, last = 0;
    renderer.__drawsWhenChanged = true;
    renderer.render = function (mode) {
      if (mode === RENDER) {
        var now = Date.now();
        if (now - last < QUIET_MS && !changed(c)) return;
        last = now;
      }
      return render.apply(this, arguments);
    };
  }
  function every() {
    if (typeof canvas === "undefined" || !canvas.activated) return;
    canvas.activated.forEach(drawWhenChanged);
  }
  every();
  setInterval(every, 250);   /* a canvas made later: the next scene, a notebook cell */
})();
