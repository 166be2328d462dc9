"""The two pages as the accessibility tests open them (tests/test_access_browser.py,
tests/test_keys_browser.py): reached cheaply, never watched running.

* LocalPage: ONE `main.py` program and its page for a whole test module, opened with
  prefers-reduced-motion (so paused at t = 0 on its first frame) in a small window, taken from
  scene to scene by its own scene menu, and to the time a check needs by Jump
  (browser_support.jump_to). A page load costs a program start and GlowScript's 4 MB of script;
  a scene from the menu costs neither.
* offline(browser, scene, folder): the scene's offline file (export/offline_page.py's page, as
  `--html` writes it, written in this process), opened from file:// with prefers-reduced-motion,
  paused at n = 0, every request but the file's own refused.
* layout_problems(page): what 200 % zoom may break: a control, graph or text cut off or lying
  over another.
"""
from __future__ import annotations

from browser_support import jump_offline, jump_to, wait_for
from test_browser import Program, shown_time

SMALL = (1024, 768)       # px: the smallest window the pages are built for; small windows draw fastest
OPENING_MS = 300_000      # the most a page may take to open (GlowScript compiles the program) on a loaded machine
GRAPH_CHOICES = {"energy graph": "Energy", "phase space": "Phase space", "energy bars": None}


class LocalPage:
    """`main.py` in a browser context of its own, started at the first scene asked for."""

    def __init__(self, browser, size=SMALL):
        self.browser, self.size = browser, size
        self.program = self.context = self.page = None
        self.scene = None
        self.opened = None      # what the page showed once open: t and the run button's text

    def show(self, scene: str):
        """The page showing `scene` at t = 0, paused: opened, or switched by the scene menu."""
        if self.page is None:
            self.program = Program(scene)
            self.context = self.browser.new_context(viewport={"width": self.size[0], "height": self.size[1]},
                                                    reduced_motion="reduce")
            self.page = self.context.new_page()
            self.page.goto(self.program.url())
            self._built(scene)
            self.opened = {"t": shown_time(self.page), "button": self.run_button()}
        elif scene != self.scene:
            self.page.get_by_role("combobox", name="scene").select_option(scene)
            self._built(scene)
        return self.page

    def _built(self, scene: str) -> None:
        page = self.page
        page.wait_for_function("s => document.title.startsWith(s + ':')", arg=scene)
        page.get_by_role("button", name="Run", exact=True).wait_for()
        wait_for(lambda: page.get_by_role("combobox", name="scene").input_value() == scene and shown_time(page) == 0.0,
                 timeout=120, what=f"{scene} built, paused at t = 0")
        self.scene = scene

    def run_button(self) -> str:
        return self.page.evaluate("""() => Array.from(document.querySelectorAll('button')).map(b => b.textContent.trim())
            .filter(t => t === 'Run' || t === 'Pause')[0]""")

    def jump(self, t: float) -> float:
        return jump_to(self.page, t)

    def measure(self) -> None:
        """The Measure panel open (it stays open from scene to scene)."""
        panel = self.page.locator(".sm-measure")
        if not panel.is_visible():
            self.page.locator(".sm-measure-toggle").click()
        panel.wait_for(state="visible")

    def choose_graph(self, choice: str) -> None:
        """The Measure panel's graph place showing `choice` (GRAPH_CHOICES), drawn."""
        page = self.page
        menu = page.get_by_role("combobox", name="graph")
        if menu.input_value() != choice:
            menu.select_option(choice)
        title = GRAPH_CHOICES[choice]
        if title is None:
            page.locator(".sm-bars").first.wait_for(state="visible")
        else:
            page.wait_for_function("""t => Array.from(document.querySelectorAll('.sm-legend .sm-title'))
                .some(e => e.offsetParent !== null && e.textContent.startsWith(t))""", arg=title)

    def describe(self) -> str:
        """Press D; the sentences for the t shown."""
        t = shown_time(self.page)
        self.page.keyboard.press("d")
        said = self.page.locator(".sm-description").filter(has_text=f"t = {t:.2f} s")
        said.wait_for()
        return said.inner_text()

    def graphs_described(self) -> None:
        """Wait until every graph shown has its text alternative (export/page_access.js)."""
        graphs_described(self.page)

    def close(self) -> None:
        if self.context is not None:
            self.context.close()
        if self.program is not None:
            self.program.stop()


def graphs_described(page) -> None:
    page.wait_for_function("""() => { const gs = Array.from(document.querySelectorAll('.glowscript-graph'))
        .filter(g => g.offsetParent !== null); return gs.length > 0 && gs.every(g => g.getAttribute('aria-label')); }""")


def open_table(page) -> None:
    """The first graph's table of the points shown, open."""
    summary = page.locator("details.sm-alt summary").first
    if not summary.evaluate("s => s.parentNode.open"):
        summary.click()
    page.locator("table.sm-points").first.wait_for()


# ---- the offline page ----

def written_page(folder, scene: str):
    """The scene's offline file, as `main.py SCENE --html FILE` writes it (export/offline_page.py)."""
    from export.offline_page import page
    from scenes import catalog

    path = folder / f"{scene}.html"
    path.write_text(page(catalog.configure(scene)), encoding="utf-8")
    return path


def offline(browser, scene: str, folder, *, size=SMALL, **context):
    """(context, page): the scene's offline file open, paused at n = 0 with a graph drawn."""
    url = written_page(folder, scene).as_uri()
    context = browser.new_context(viewport={"width": size[0], "height": size[1]}, reduced_motion="reduce", **context)
    context.route("**/*", lambda route: route.continue_() if route.request.url.split("#")[0] == url else route.abort())
    page = context.new_page()
    page.goto(url)
    page.wait_for_function("() => window.offlineState && window.offlineState().paused && "
                           "document.querySelector('.glowscript-graph')", timeout=OPENING_MS)
    return context, page


def offline_step(page, times: int = 1) -> int:
    for _ in range(times):
        n = page.evaluate("() => window.offlineState().n || 0")
        page.click("#step-button")
        page.wait_for_function("n => window.offlineState().n > n", arg=n)
    return page.evaluate("() => window.offlineState().n")


def offline_jump(page, t: float) -> dict:
    return jump_offline(page, t)


# ---- 200 % zoom ----

# Every control, picture and legend entry shown, each line of text, and what may hide them: a
# thing cut off by a box that hides what overflows it (the page's own, or the window's sides), and
# any two that lie over each other (neither inside the other), by more than 4 px².
LAYOUT_PROBLEMS = """() => {
  const SHOWN = 'button, select, input:not([type=hidden]):not([type=file]), textarea, summary, a[href], .ui-slider, ' +
                '.glowscript-canvas-wrapper, .glowscript-graph, .sm-entry, svg.sm-sample';
  const clipped = e => { for (let a = e; a; a = a.parentElement) if (getComputedStyle(a).clip !== 'auto') return true; return false; };
  const seen = e => { const r = e.getBoundingClientRect(), s = getComputedStyle(e);
    return r.width > 0 && r.height > 0 && s.visibility !== 'hidden' && !e.closest('details:not([open]) > :not(summary)') &&
           !clipped(e); };   // a clipped element is heard, not seen (a screen reader's words)
  const name = e => (e.tagName + (e.id ? '#' + e.id : '') + (typeof e.className === 'string' && e.className ?
    '.' + e.className.trim().split(/\\s+/)[0] : '') + ' "' + (e.textContent || e.value || '').trim().slice(0, 30) + '"');
  const items = Array.from(document.querySelectorAll(SHOWN)).filter(seen).map(e => ({e, r: e.getBoundingClientRect()}));
  const texts = [];
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    const p = n.parentElement;
    if (!n.textContent.trim() || !p || p.closest('script, style, option') || !seen(p)) continue;
    const range = document.createRange(); range.selectNodeContents(n);
    for (const r of range.getClientRects()) if (r.width > 1 && r.height > 1) texts.push({e: p, r, text: n.textContent.trim().slice(0, 30)});
  }
  const over = (a, b) => Math.max(0, Math.min(a.right, b.right) - Math.max(a.left, b.left)) *
                         Math.max(0, Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top));
  const problems = [];
  const W = document.documentElement.scrollWidth, H = document.documentElement.scrollHeight;
  for (const {e, r} of items.concat(texts)) {
    const x = r.left + window.scrollX, y = r.top + window.scrollY;
    if (x < -1 || y < -1 || x + r.width > W + 1 || y + r.height > H + 1)
      problems.push('off the page (' + [x, y, x + r.width, y + r.height].map(Math.round) + ' in ' + [W, H] + '): ' + name(e));
    for (let a = e.parentElement; a; a = a.parentElement) {
      const s = getComputedStyle(a);
      if (!/hidden|clip/.test(s.overflowX + ' ' + s.overflowY) || a.matches('.glowscript-canvas-wrapper')) continue;
      const b = a.getBoundingClientRect();
      const wide = /hidden|clip/.test(s.overflowX), tall = /hidden|clip/.test(s.overflowY);
      if ((wide && (r.left < b.left - 1 || r.right > b.right + 1)) || (tall && (r.top < b.top - 1 || r.bottom > b.bottom + 1)))
        { problems.push('cut off by ' + name(a) + ': ' + name(e)); break; }
    }
  }
  for (let i = 0; i < items.length; i++) for (let j = i + 1; j < items.length; j++) {
    const a = items[i], b = items[j];
    if (a.e.contains(b.e) || b.e.contains(a.e)) continue;
    if (over(a.r, b.r) > 4) problems.push('overlap: ' + name(a.e) + ' and ' + name(b.e));
  }
  for (const t of texts) for (const {e, r} of items) {
    if (e.contains(t.e) || t.e.contains(e)) continue;
    if (over(t.r, r) > 4) problems.push('text "' + t.text + '" under ' + name(e));
  }
  return Array.from(new Set(problems));
}"""


def layout_problems(page) -> list[str]:
    return page.evaluate(LAYOUT_PROBLEMS)


def zoomed(page, *, window=(1280, 800), zoom: float = 2.0) -> None:
    """The page as a browser at `zoom` (Ctrl and + to 200 %) shows it in a `window` px window: the
    layout sees window / zoom CSS px, and each CSS px is drawn with zoom device px (Chromium's
    device scale factor, set on the open page through the DevTools protocol, as Playwright's own
    emulation sets it), so the page and its canvases are laid out and drawn as zoomed."""
    session = page.context.new_cdp_session(page)
    session.send("Emulation.setDeviceMetricsOverride", {"width": round(window[0] / zoom), "height": round(window[1] / zoom),
                                                         "deviceScaleFactor": zoom, "mobile": False})
    page.wait_for_function("w => window.innerWidth === w", arg=round(window[0] / zoom))
    settled(page)


def settled(page) -> None:
    """The page laid out for its window now (the local page's layout, browser/page_layout.py, runs
    on a resize and twice a second), and two frames drawn since."""
    page.evaluate("() => { if (window.smLayout) window.smLayout(); }")
    page.evaluate("() => new Promise(done => requestAnimationFrame(() => requestAnimationFrame(done)))")
