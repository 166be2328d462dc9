// Added at the top of vpython's page (glowcomm.html) by browser/server/http_server.py.
//
// 1. It tells the server at once that a browser is loading this page ("/loading"): a browser too
//    old to say so in its Sec-Fetch-Mode header is then still known to be reloading the page.
// 2. When the page's websocket closes, it says why on the page instead of leaving it blank or
//    frozen (vpython's own page only tries window.close(), which browsers ignore for a tab the
//    user opened). "/status" tells a second tab ("busy") from a program that has ended.
(function () {
  fetch('/loading', {cache: 'no-store'}).catch(function () {});
  var Real = window.WebSocket;
  function say(html) {
    var box = document.getElementById('tab-message') || document.createElement('div');
    box.id = 'tab-message';
    box.style.cssText = 'position:fixed;top:0;left:0;right:0;z-index:1000;padding:16px;' +
      'background:#fff4c2;color:#222;font:20px sans-serif;border-bottom:2px solid #c90';
    box.innerHTML = html;
    document.body.appendChild(box);
  }
  window.WebSocket = function (url, protocols) {
    var ws = protocols === undefined ? new Real(url) : new Real(url, protocols);
    var opened = false;
    ws.addEventListener('open', function () { opened = true; });
    ws.addEventListener('close', function () {
      fetch('/status', {cache: 'no-store'}).then(function (r) { return r.text(); }).then(function (t) {
        if (t === 'busy') {
          say('This scene is already open in another tab. Use that tab, or close it and reload this one.');
        } else if (opened) {
          say('The connection to the program was lost. Reload this tab to see the scene again.');
        } else {
          say('This page could not connect to the program. Reload this tab to try again.');
        }
      }, function () {
        say('The program has ended, so this page no longer changes. ' +
            'Run <code>python main.py</code> again to start it.');
      });
    });
    return ws;
  };
  window.WebSocket.prototype = Real.prototype;
  ['CONNECTING', 'OPEN', 'CLOSING', 'CLOSED'].forEach(function (k) { window.WebSocket[k] = Real[k]; });
})();
