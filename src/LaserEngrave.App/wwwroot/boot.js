// Starts the page's connection with the start's token. The token lives in this tab's sessionStorage, which only this
// origin (scheme, host and port) can read: never in a cookie, which the browser would send to every port on 127.0.0.1,
// and never in an address. The address the page is opened at carries a one-time launch code (#launch=CODE), traded
// once for the token: what the history keeps of it opens nothing.
(async function () {
  'use strict';
  const key = 'laserengrave-token';
  const address = new URL(location.href);
  const code = new URLSearchParams(address.hash.slice(1)).get('launch');
  if (code) {
    // The code leaves the address bar at once; it is used up by the trade below in any case.
    address.hash = '';
    history.replaceState(history.state, '', address.pathname + address.search);
    try {
      const traded = await fetch('api/session', { method: 'POST', headers: { 'X-LaserEngrave-Launch': code }, credentials: 'omit', cache: 'no-store' });
      if (traded.ok) {
        sessionStorage.setItem(key, (await traded.json()).token);
      }
    } catch (e) {
      // Refused below, as a page without a token.
    }
  }

  const token = () => sessionStorage.getItem(key);

  function refuse() {
    sessionStorage.removeItem(key);
    document.body.innerHTML = '';
    const message = document.createElement('p');
    message.id = 'no-token';
    message.style.margin = '2rem';
    message.textContent = 'Open LaserEngrave from the window it opened or the launch address it printed when it started (each works once).';
    document.body.append(message);
  }

  // Requests of the page's own (the mask, a log export) show the token as scripts do.
  async function authorisedFetch(url, init) {
    const headers = new Headers(init && init.headers);
    headers.set('Authorization', 'Bearer ' + token());
    return fetch(url, { ...init, headers, credentials: 'omit' });
  }

  window.laserEngrave = { fetch: authorisedFetch };

  // A link to the API (a log export, a run's log) is fetched with the token: a download is saved under the server's
  // file name, a link to a new tab opens what was fetched there (a tab opened at the API's address would have no token).
  document.addEventListener('click', async (e) => {
    const link = e.target instanceof Element ? e.target.closest('a[href^="api/"]:is([download], [target="_blank"])') : null;
    if (!link) return;
    e.preventDefault();
    e.stopPropagation();
    if (!link.hasAttribute('download')) {
      // Opened now, within the click, so no pop-up blocker stops it; filled once the answer is here.
      const tab = window.open('', '_blank');
      const shown = await authorisedFetch(link.getAttribute('href'));
      const text = shown.ok ? await shown.blob() : new Blob([await shown.text()], { type: 'text/plain' });
      if (tab) tab.location.href = URL.createObjectURL(text);
      return;
    }

    // A link that asks for it (the job file) offers the browser's own save dialog where there is one (the File System
    // Access API, in Chromium browsers), asked within the click; elsewhere, or if it fails, it downloads as any link.
    const picked = link.hasAttribute('data-save-picker') && window.showSaveFilePicker
      ? window.showSaveFilePicker({ suggestedName: link.getAttribute('download') || undefined, types: [{ description: 'Job file', accept: { 'application/json': ['.json'] } }] })
        .catch((error) => (error && error.name === 'AbortError' ? 'cancelled' : null))
      : null;
    const response = await authorisedFetch(link.getAttribute('href'));
    if (!response.ok) return;
    const handle = await picked;
    if (handle === 'cancelled') return;
    if (handle) {
      try {
        const writable = await handle.createWritable();
        await writable.write(await response.clone().blob());
        await writable.close();
        return;
      } catch (e) {
        // Written nowhere: downloaded below instead.
      }
    }

    const disposition = response.headers.get('Content-Disposition') || '';
    const name = /filename\*?=(?:UTF-8'')?"?([^";]+)"?/i.exec(disposition);
    const url = URL.createObjectURL(await response.blob());
    const save = document.createElement('a');
    save.href = url;
    save.download = name ? decodeURIComponent(name[1]) : '';
    document.body.append(save);
    save.click();
    save.remove();
    setTimeout(() => URL.revokeObjectURL(url), 60000);
  }, true);

  if (!token()) {
    refuse();
    return;
  }

  // A token of an earlier start (the app restarted on this port) is refused here: Blazor would wait on its circuit.
  authorisedFetch('api/state').then((response) => {
    if (response.status === 401) {
      refuse();
      return;
    }

    Blazor.start({
      circuit: {
        configureSignalR: (builder) => builder.withUrl('_blazor', { accessTokenFactory: token }),
      },
    });
  }, refuse);
})();
