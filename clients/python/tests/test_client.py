"""The client gives the token to the app alone: not to a proxy, not across a redirect, not to a server on the port
that cannot prove it holds the token, not when the app named in connection.json has ended, never off this computer.

    python3 -m unittest discover -s clients/python/tests

Run by tests/LaserEngrave.App.Tests (AppProcessTests.PythonClient_UnitTests_AllPass) with the rest of the suite.
"""

import hashlib
import hmac
import http.server
import json
import os
import subprocess
import sys
import tempfile
import threading
import unittest
import urllib.parse

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from laserengrave import ApiError, LaserEngrave  # noqa: E402

TOKEN = "t0ken-of-this-start-0123456789abcdefghijklmn"


class Recorder:
    """A local HTTP server that records every request's first line and headers and answers as told."""

    def __init__(self, answer):
        self.requests = []
        recorder = self

        class Handler(http.server.BaseHTTPRequestHandler):
            def log_message(self, *args):
                pass

            def handle_one(self):
                recorder.requests.append((self.command, self.path, dict(self.headers)))
                status, headers, body = answer(self)
                self.send_response(status)
                for key, value in headers.items():
                    self.send_header(key, value)
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

            do_GET = do_POST = do_CONNECT = handle_one

        self.server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}"
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()

    def close(self):
        self.server.shutdown()
        self.server.server_close()

    def saw_token(self):
        return any(TOKEN in json.dumps(headers) or TOKEN in path for _, path, headers in self.requests)


def app_answer(token=TOKEN, pid=None, redirect_to=None):
    """The app as the client expects it: GET /api/proof answers the HMAC of the challenge; other routes {}."""

    def answer(handler):
        url = urllib.parse.urlsplit(handler.path)
        if url.path == "/api/proof":
            challenge = urllib.parse.parse_qs(url.query)["challenge"][0]
            proof = hmac.new(token.encode(), ("laserengrave-proof:" + challenge).encode(), hashlib.sha256).hexdigest()
            body = {"app": "LaserEngrave", "pid": pid if pid is not None else os.getpid(), "proof": proof}
            return 200, {"Content-Type": "application/json"}, json.dumps(body).encode()
        if redirect_to:
            return 302, {"Location": redirect_to + url.path}, b""
        return 200, {"Content-Type": "application/json"}, b"{}"

    return answer


class ClientTests(unittest.TestCase):
    def setUp(self):
        self.servers = []

    def tearDown(self):
        for server in self.servers:
            server.close()

    def serve(self, answer):
        server = Recorder(answer)
        self.servers.append(server)
        return server

    def test_state_proxyInTheEnvironment_SentToTheAppNeverThroughTheProxy(self):
        app = self.serve(app_answer())
        proxy = self.serve(lambda h: (200, {"Content-Type": "application/json"}, b"{}"))
        environment = dict(os.environ)
        for name in ("http_proxy", "HTTP_PROXY", "all_proxy", "ALL_PROXY"):
            environment[name] = proxy.url
        for name in ("no_proxy", "NO_PROXY"):
            environment.pop(name, None)

        # A script of its own, as a user's runs: urllib reads the proxy settings once a process.
        client = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
        script = f"import sys; sys.path.insert(0, {client!r}); from laserengrave import LaserEngrave; LaserEngrave({app.url!r}, {TOKEN!r}).state()"
        subprocess.run([sys.executable, "-c", script], env=environment, check=True, timeout=60)

        self.assertEqual([], proxy.requests)
        self.assertTrue(app.saw_token())

    def test_state_redirectToAnotherLocalPort_NotFollowedAndTheTokenNotSentThere(self):
        elsewhere = self.serve(lambda h: (200, {"Content-Type": "application/json"}, b"{}"))
        app = self.serve(app_answer(redirect_to=elsewhere.url))

        with self.assertRaises(ApiError) as raised:
            LaserEngrave(app.url, TOKEN).state()

        self.assertEqual(302, raised.exception.status)
        self.assertIn("redirect", raised.exception.message)
        self.assertEqual([], elsewhere.requests)

    def test_state_serverOnThePortCannotProveTheToken_RefusedAndTheTokenNeverSent(self):
        impostor = self.serve(app_answer(token="another-start"))

        with self.assertRaises(ApiError) as raised:
            LaserEngrave(impostor.url, TOKEN).state()

        self.assertIn("could not prove", raised.exception.message)
        self.assertFalse(impostor.saw_token())
        self.assertEqual(["/api/proof"], [urllib.parse.urlsplit(p).path for _, p, _ in impostor.requests])

    def test_state_serverWithoutTheProofRoute_RefusedAndTheTokenNeverSent(self):
        other = self.serve(lambda h: (404, {"Content-Type": "text/plain"}, b"not found"))

        with self.assertRaises(ApiError):
            LaserEngrave(other.url, TOKEN).state()

        self.assertFalse(other.saw_token())

    def test_fromConnectionFile_TheAppsProcessHasEnded_RefusedAndNothingSent(self):
        ended = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True, check=True)
        pid = int(ended.stdout)
        port_taker = self.serve(app_answer(pid=pid))
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "connection.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump({"url": port_taker.url, "token": TOKEN, "pid": pid}, f)

            with self.assertRaises(ApiError) as raised:
                LaserEngrave.from_connection_file(path).state()

        self.assertIn("has ended", raised.exception.message)
        self.assertEqual([], port_taker.requests)

    def test_fromConnectionFile_AnotherProcessAnswers_RefusedAndTheTokenNeverSent(self):
        # The app named in the file is alive (this process), but the server on the port is another process.
        other = self.serve(app_answer(pid=os.getpid() + 1))
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "connection.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump({"url": other.url, "token": TOKEN, "pid": os.getpid()}, f)

            with self.assertRaises(ApiError) as raised:
                LaserEngrave.from_connection_file(path).state()

        self.assertIn("not " + str(os.getpid()), raised.exception.message)
        self.assertFalse(other.saw_token())

    def test_new_NotALoopbackAddress_Refused(self):
        for url in ("http://192.0.2.7:5080", "http://localhost:5080", "https://127.0.0.1:5080", "http://127.0.0.1", "http://user:pw@127.0.0.1:5080", "http://[::ffff:192.0.2.7]:5080"):
            with self.subTest(url=url), self.assertRaises(ApiError) as raised:
                LaserEngrave(url, TOKEN)
            self.assertIn("not the app's address", raised.exception.message)

    def test_new_LoopbackAddresses_Taken(self):
        for url in ("http://127.0.0.1:5080", "http://[::1]:5080", "http://127.1.2.3:5080/"):
            with self.subTest(url=url):
                self.assertEqual(url.rstrip("/"), LaserEngrave(url, TOKEN).url)


if __name__ == "__main__":
    unittest.main()
