// Starts the page's connection with the start's token. The token lives in this tab's sessionStorage, which only this
// origin (scheme, host and port) can read: never in a cookie, which the browser would send to every port on 127.0.0.1.
(function () {
  'use strict';
  const key = 'laserengrave-token';
  const address = new URL(location.href);
  const given = address.searchParams.get('token');
  if (given) {
    sessionStorage.setItem(key, given);
    // The token leaves the address bar (and the history) at once.
    address.searchParams.delete('token');
    history.replaceState(history.state, '', address);
  }

  const token = () => sessionStorage.getItem(key);

  function refuse() {
    sessionStorage.removeItem(key);
    document.body.innerHTML = '';
    const message = document.createElement('p');
    message.id = 'no-token';
    message.style.margin = '2rem';
    message.textContent = 'Open the address LaserEngrave printed when it started (it carries this start\u2019s token).';
    document.body.append(message);
  }

  // Requests of the page's own (the mask, a log export) show the token as scripts do.
  async function authorisedFetch(url, init) {
    const headers = new Headers(init && init.headers);
    headers.set('Authorization', 'Bearer ' + token());
    return fetch(url, { ...init, headers, credentials: 'omit' });
  }

  window.laserEngrave = { fetch: authorisedFetch };

  // A download link to the API (a log export) is fetched with the token, then saved under the server's file name.
  document.addEventListener('click', async (e) => {
    const link = e.target instanceof Element ? e.target.closest('a[download][href^="api/"]') : null;
    if (!link) return;
    e.preventDefault();
    e.stopPropagation();
    const response = await authorisedFetch(link.getAttribute('href'));
    if (!response.ok) return;
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
