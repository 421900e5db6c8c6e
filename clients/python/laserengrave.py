"""A small client for the LaserEngrave app's HTTP API (docs/api.md, docs/openapi.json), standard library only.

    from laserengrave import LaserEngrave
    app = LaserEngrave.from_connection_file()        # the running app's address and token
    app.upload("mark.png")                           # or app.open_file("/abs/path/drawing.dxf")
    app.set_job(widthMm=2, originXMm=5, originYMm=5, burnSpeedMmPerS=2, laserFrequencyHz=2000)
    app.connect(simulator=True)
    run = app.run(sample_id="S-1", progress=print)   # start, wait for the end; the run's log summary
    record = app.export_log(run["path"])             # the run's JSON record

Every request shows the start's token (Authorization: Bearer); the app refuses requests without it (401) and any
with another page's Origin (403). Nothing here sends an Origin or a cookie. The token goes to the app alone: only to a
loopback address (127.0.0.1, [::1]), never through a proxy (http_proxy, the Windows registry's), never across a
redirect, and only after the server on the port has proved it holds the token (GET /api/proof, an HMAC of a fresh
challenge) and, with a connection file, that the app's process named there is alive: a connection.json left by a crash
sends nothing to whoever took the freed port.
"""

import hashlib
import hmac
import ipaddress
import json
import os
import secrets
import sys
import time
import urllib.error
import urllib.parse
import urllib.request

__all__ = ["LaserEngrave", "ApiError", "RunError", "default_connection_file"]

# The run states in which a run is still under way (state.run.state).
_UNDER_WAY = {"Running", "Paused", "Aborting", "Pausing", "Preflight"}


class ApiError(Exception):
    """The app refused a request: status is the HTTP status, message the app's one line (or its field errors)."""

    def __init__(self, status, message, body=None):
        super().__init__(f"{status}: {message}")
        self.status = status
        self.message = message
        self.body = body


class _NoRedirect(urllib.request.HTTPRedirectHandler):
    """Follows no redirect: the answer stays the 3xx (raised as ApiError), so the token never goes to another address."""

    def redirect_request(self, req, fp, code, msg, headers, newurl):
        return None


# No proxy (an empty ProxyHandler: http_proxy and the Windows registry's proxy are not read) and no redirects.
_OPENER = urllib.request.build_opener(urllib.request.ProxyHandler({}), _NoRedirect())


def _loopback_url(url):
    """url when it is http:// on a loopback address (127.0.0.0/8, [::1]); ApiError otherwise. Names (localhost) are refused: a hosts file could send them elsewhere."""
    parts = urllib.parse.urlsplit(url)
    try:
        loopback = parts.scheme == "http" and parts.hostname is not None and ipaddress.ip_address(parts.hostname).is_loopback
        port = parts.port
    except ValueError:
        loopback, port = False, None
    if not loopback or port is None or parts.username or parts.password:
        raise ApiError(0, f"{url}: not the app's address: the token is sent only to http://127.0.0.1:PORT or http://[::1]:PORT")
    return url.rstrip("/")


def _process_alive(pid):
    """Whether a process with this id runs (the app that wrote connection.json)."""
    if pid <= 0:
        return False
    if sys.platform == "win32":
        import ctypes
        kernel32 = ctypes.windll.kernel32
        handle = kernel32.OpenProcess(0x1000, False, pid)  # PROCESS_QUERY_LIMITED_INFORMATION
        if not handle:
            return False
        try:
            code = ctypes.c_ulong()
            return bool(kernel32.GetExitCodeProcess(handle, ctypes.byref(code))) and code.value == 259  # STILL_ACTIVE
        finally:
            kernel32.CloseHandle(handle)
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


class RunError(Exception):
    """A run that did not complete; run is its log summary (outcome, error, path) when it left one."""

    def __init__(self, message, run=None):
        super().__init__(message)
        self.run = run


def default_connection_file():
    """Where the app writes connection.json by default: its data folder (.NET's ApplicationData/LaserEngrave)."""
    if os.environ.get("LASERENGRAVE_CONNECTION"):
        return os.environ["LASERENGRAVE_CONNECTION"]
    if sys.platform == "win32":
        base = os.environ.get("APPDATA") or os.path.expanduser(r"~\AppData\Roaming")
    elif sys.platform == "darwin":
        base = os.path.expanduser("~/Library/Application Support")
    else:
        base = os.environ.get("XDG_CONFIG_HOME") or os.path.expanduser("~/.config")
    return os.path.join(base, "LaserEngrave", "connection.json")


class LaserEngrave:
    """The running app at url, shown the token on every request."""

    def __init__(self, url, token, timeout=30.0, pid=None):
        self.url = _loopback_url(url)
        self.token = token
        self.timeout = timeout
        self.pid = pid
        self._verified = False

    def verify(self):
        """Checks the server on the port is this start of the app before the token is sent: the process named in
        connection.json is alive, and the server proves it holds the token (HMAC-SHA256 keyed by the token over
        'laserengrave-proof:' + a fresh challenge, GET /api/proof). Raises ApiError when it is not."""
        if self.pid is not None and not _process_alive(self.pid):
            raise ApiError(0, f"{self.url}: the app's process {self.pid} named in the connection file has ended: is LaserEngrave running?")
        challenge = secrets.token_urlsafe(24)
        request = urllib.request.Request(self.url + "/api/proof?challenge=" + challenge, method="GET", headers={"Accept": "application/json"})
        try:
            with _OPENER.open(request, timeout=self.timeout) as response:
                answer = _json_or_none(response.read())
        except urllib.error.HTTPError as e:
            raise ApiError(0, f"{self.url}: the server there is not LaserEngrave (it answered {e.code} to the proof): the token was not sent") from None
        except urllib.error.URLError as e:
            raise ApiError(0, f"{self.url}: cannot reach LaserEngrave ({e.reason})") from None
        expected = hmac.new(self.token.encode("ascii"), ("laserengrave-proof:" + challenge).encode("ascii"), hashlib.sha256).hexdigest()
        proof = answer.get("proof") if isinstance(answer, dict) else None
        if not isinstance(proof, str) or not hmac.compare_digest(proof, expected):
            raise ApiError(0, f"{self.url}: the server there could not prove it is this start of LaserEngrave (a connection file left by an earlier start?): the token was not sent")
        if self.pid is not None and answer.get("pid") != self.pid:
            raise ApiError(0, f"{self.url}: the server there is process {answer.get('pid')}, not {self.pid} named in the connection file: the token was not sent")
        self._verified = True

    @classmethod
    def from_connection_file(cls, path=None, timeout=30.0):
        """The app whose connection.json is at path (default: the app's data folder, or $LASERENGRAVE_CONNECTION)."""
        path = path or default_connection_file()
        try:
            with open(path, encoding="utf-8") as f:
                connection = json.load(f)
        except FileNotFoundError:
            raise ApiError(0, f"{path}: no such file: is LaserEngrave running (it writes the file at start)?") from None
        except (OSError, ValueError) as e:
            raise ApiError(0, f"{path}: not a LaserEngrave connection file ({e})") from None
        if not isinstance(connection, dict) or not connection.get("url") or not connection.get("token"):
            raise ApiError(0, f"{path}: not a LaserEngrave connection file (no url and token)")
        pid = connection.get("pid")
        return cls(connection["url"], connection["token"], timeout, pid if isinstance(pid, int) and pid > 0 else None)

    # --- HTTP ---------------------------------------------------------------------------------------------------

    def request(self, method, path, body=None, data=None, content_type=None, raw=False):
        """One API call; returns the parsed JSON answer (or bytes with raw=True). Raises ApiError for 3xx, 4xx and 5xx."""
        if not self._verified:
            self.verify()
        headers = {"Authorization": f"Bearer {self.token}", "Accept": "application/json"}
        if body is not None:
            data = json.dumps(body).encode("utf-8")
            content_type = "application/json"
        if content_type:
            headers["Content-Type"] = content_type
        if method == "POST" and data is None:
            data = b"{}"
            headers["Content-Type"] = "application/json"
        request = urllib.request.Request(self.url + path, data=data, method=method, headers=headers)
        try:
            with _OPENER.open(request, timeout=self.timeout) as response:
                content = response.read()
        except urllib.error.HTTPError as e:
            if 300 <= e.code < 400:
                raise ApiError(e.code, f"{self.url}: the server answered with a redirect to {e.headers.get('Location')}; not followed (the token goes to the app alone)") from None
            content = e.read()
            raise ApiError(e.code, _message(content, e.reason), _json_or_none(content)) from None
        except urllib.error.URLError as e:
            raise ApiError(0, f"{self.url}: cannot reach LaserEngrave ({e.reason})") from None
        if raw:
            return content
        return json.loads(content) if content else None

    def state(self):
        """The whole state (GET /api/state)."""
        return self.request("GET", "/api/state")

    # --- the job ------------------------------------------------------------------------------------------------

    def upload(self, path, name=None):
        """Sends an image or drawing file's bytes; the app keeps it under its images/ and opens it."""
        with open(path, "rb") as f:
            data = f.read()
        name = name or os.path.basename(path)
        state = self.request("POST", "/api/image?name=" + urllib.parse.quote(name), data=data, content_type="application/octet-stream")
        return _opened(state, name)

    def open_file(self, path):
        """Opens an image or drawing file that is on the app's computer (an absolute path)."""
        state = self.request("POST", "/api/image/open", {"path": os.path.abspath(path)})
        return _opened(state, path)

    def set_job(self, **fields):
        """Changes job values (widthMm, originXMm, burnSpeedMmPerS, laserFrequencyHz, ...: docs/api.md); the new state."""
        try:
            state = self.request("POST", "/api/job", fields)
        except ApiError as e:
            if e.status == 400 and isinstance(e.body, dict) and e.body.get("errors"):
                raise ApiError(400, "; ".join(e.body["errors"].values()), e.body) from None
            raise
        errors = state["job"].get("errors") or {}
        if errors:
            raise ApiError(400, "; ".join(f"{v}" for v in errors.values()), state)
        return state

    # --- the machine --------------------------------------------------------------------------------------------

    def connect(self, simulator=True, stage_port=None, laser_port=None, timeout=60.0):
        """Connects (the built-in simulator, or the two serial ports) and waits until the machine is ready."""
        self.request("POST", "/api/machine/connect", {"useSimulator": simulator, "stagePort": stage_port, "laserPort": laser_port})
        state = self._wait(lambda s: not s["activity"]["busy"], timeout, "the connection")
        machine = state["machine"]
        if not machine["connected"]:
            raise ApiError(409, machine.get("error") or "not connected")
        return state

    def home(self, timeout=120.0):
        """Homes both axes (laser off) and waits for the end."""
        self.request("POST", "/api/machine/home")
        return self._wait(lambda s: not s["activity"]["busy"], timeout, "homing")

    # --- runs ---------------------------------------------------------------------------------------------------

    def start(self, sample_id=None, notes=None):
        """Starts the planned job; returns the log path the last run had before, to tell this run's log apart."""
        before = self.state()["log"]["lastRun"]
        answer = self.request("POST", "/api/run/start", {"sampleId": sample_id, "notes": notes})
        if isinstance(answer, dict) and answer.get("note"):
            raise RunError(answer["note"])
        return before["path"] if before else None

    def wait_for_run(self, previous_log=None, progress=None, poll=0.5, timeout=None):
        """Waits for the run started after previous_log to end; progress(run) is called at each poll with state.run.

        Returns the run's log summary (state.log.lastRun: path, outcome, sampleId, actualSeconds, text); raises RunError
        when the run did not complete (aborted, failed) or ended without a log.
        """
        end = None if timeout is None else time.monotonic() + timeout
        while True:
            state = self.state()
            run, last = state["run"], state["log"]["lastRun"]
            if progress:
                progress(run)
            new_log = last is not None and last["path"] != previous_log
            if not run["active"] and run["state"] not in _UNDER_WAY:
                if new_log:
                    if last["outcome"] != "completed":
                        raise RunError(f"the run ended {last['outcome']}: {last.get('error') or run.get('error') or ''}".rstrip(": "), last)
                    return last
                if run.get("error"):
                    raise RunError(run["error"])
            if end is not None and time.monotonic() > end:
                raise RunError(f"the run had not ended after {timeout} s (state {run['state']}, {run['percent']} %)")
            time.sleep(poll)

    def run(self, sample_id=None, notes=None, progress=None, poll=0.5, timeout=None):
        """Starts the planned job and waits for its end (see wait_for_run); the run's log summary."""
        previous = self.start(sample_id, notes)
        return self.wait_for_run(previous, progress, poll, timeout)

    def abort(self):
        """Aborts the run under way (laser off first)."""
        return self.request("POST", "/api/run/abort")

    def export_log(self, path, fmt="json"):
        """A logged run's record: the JSON record as a dict (fmt="json") or the text summary (fmt="txt")."""
        query = urllib.parse.urlencode({"path": path, "format": fmt})
        content = self.request("GET", "/api/logs/export?" + query, raw=True)
        return json.loads(content) if fmt == "json" else content.decode("utf-8")

    def _wait(self, condition, timeout, what, poll=0.2):
        end = time.monotonic() + timeout
        while True:
            state = self.state()
            if condition(state):
                return state
            if time.monotonic() > end:
                raise ApiError(0, f"{what} had not ended after {timeout} s")
            time.sleep(poll)


def _opened(state, name):
    error = (state["job"].get("errors") or {}).get("image")
    if error:
        raise ApiError(400, error, state)
    return state


def _json_or_none(content):
    try:
        return json.loads(content) if content else None
    except ValueError:
        return None


def _message(content, reason):
    body = _json_or_none(content)
    if isinstance(body, dict):
        if body.get("error"):
            return body["error"]
        if body.get("errors"):
            return "; ".join(body["errors"].values())
    text = content.decode("utf-8", "replace").strip() if content else ""
    return text or str(reason)
