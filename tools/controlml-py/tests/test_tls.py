"""controlml.py's TLS: the client trusts the CA of --ca-file only and checks the host name; a certificate from
another CA, for another name or expired is refused with one line (exit 3); no silent fallback to a plain stream. TLS
handshakes on loopback sockets inside the test, and a scripted XMPP server on one (no real server, no network), with
certificates that openssl makes the way product/bin/sabot-xmpp makes the lab CA's."""

import gc
import hashlib
import io
import os
import re
import socket
import ssl
import subprocess
import sys
import tempfile
import threading
import unittest
from contextlib import redirect_stderr
from unittest import mock

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import controlml  # noqa: E402


def openssl(*args: str) -> None:
    subprocess.run(["openssl", *args], check=True, capture_output=True)


def make_ca(d: str, name: str) -> str:
    openssl("req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes", "-days", "1",
            "-subj", f"/CN={name}", "-addext", "basicConstraints=critical,CA:TRUE", "-keyout",
            os.path.join(d, f"{name}.key"), "-out", os.path.join(d, f"{name}.pem"))
    return os.path.join(d, f"{name}.pem")


def make_leaf(d: str, ca: str, domain: str) -> tuple[str, str]:
    key, crt = os.path.join(d, f"{domain}.key"), os.path.join(d, f"{domain}.crt")
    openssl("req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes", "-days", "1",
            "-CA", ca, "-CAkey", ca[:-4] + ".key", "-subj", f"/CN={domain}", "-addext",
            f"subjectAltName=DNS:{domain},DNS:*.{domain}", "-addext", "basicConstraints=critical,CA:FALSE",
            "-keyout", key, "-out", crt)
    return crt, key


def make_expired_leaf(d: str, ca: str, domain: str) -> tuple[str, str]:
    """A certificate for ``domain`` signed by ``ca`` whose validity ended a day before it began (now)."""
    key, csr, crt, ext = (os.path.join(d, f"expired.{x}") for x in ("key", "csr", "crt", "ext"))
    with open(ext, "w", encoding="ascii") as f:
        f.write(f"subjectAltName=DNS:{domain}\nbasicConstraints=critical,CA:FALSE\n")
    openssl("req", "-new", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes", "-subj",
            f"/CN={domain}", "-keyout", key, "-out", csr)
    openssl("x509", "-req", "-in", csr, "-CA", ca, "-CAkey", ca[:-4] + ".key", "-days", "-1", "-extfile", ext,
            "-out", crt)
    return crt, key


def handshake(client: ssl.SSLContext, crt: str, key: str, name: str) -> None:
    """A TLS handshake between ``client`` (expecting ``name``) and a loopback server presenting ``crt``."""
    server = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
    server.load_cert_chain(crt, key)
    with socket.create_server(("127.0.0.1", 0)) as listener:
        port = listener.getsockname()[1]

        def serve() -> None:
            conn, _ = listener.accept()
            try:
                with server.wrap_socket(conn, server_side=True):
                    pass
            except (ssl.SSLError, OSError):
                pass  # the client refused the certificate

        t = threading.Thread(target=serve, daemon=True)
        t.start()
        with socket.create_connection(("127.0.0.1", port), timeout=5) as raw:
            with client.wrap_socket(raw, server_hostname=name):
                pass
        t.join(5)


def refusal(client: ssl.SSLContext, crt: str, key: str, name: str) -> ssl.SSLError:
    """What ``client`` raises in a handshake that must fail."""
    try:
        handshake(client, crt, key, name)
    except ssl.SSLError as e:
        return e
    raise AssertionError(f"the handshake for {name} succeeded")


# --- a scripted XMPP server: one connection, the stream features given, STARTTLS with the certificate given ---------
STREAM = re.compile(rb"<stream:stream[^>]*>")
HEADER = (b"<?xml version='1.0'?><stream:stream xmlns='jabber:client' xmlns:stream='http://etherx.jabber.org/streams' "
          b"id='s1' from='sabot.local' version='1.0'>")
STARTTLS_REQUIRED = (b"<stream:features><starttls xmlns='urn:ietf:params:xml:ns:xmpp-tls'><required/></starttls>"
                     b"</stream:features>")
SASL = (b"<stream:features><mechanisms xmlns='urn:ietf:params:xml:ns:xmpp-sasl'><mechanism>SCRAM-SHA-1</mechanism>"
        b"<mechanism>PLAIN</mechanism></mechanisms></stream:features>")
PROCEED = b"<proceed xmlns='urn:ietf:params:xml:ns:xmpp-tls'/>"
NOT_AUTHORIZED = b"<failure xmlns='urn:ietf:params:xml:ns:xmpp-sasl'><not-authorized/></failure>"


def read_until(sock, pattern: re.Pattern, buf: bytes = b"") -> bytes:
    while not pattern.search(buf):
        chunk = sock.recv(4096)
        if not chunk:
            raise EOFError(buf)
        buf += chunk
    return buf


class ScriptedServer(threading.Thread):
    """Offers STARTTLS (required) and presents ``crt``, or, with ``crt`` None, offers no STARTTLS but SASL at once.
    After TLS it offers SASL and refuses the login. ``events``: what the client did, in order."""

    def __init__(self, crt: str | None, key: str | None):
        super().__init__(daemon=True)
        self.crt, self.key = crt, key
        self.listener = socket.create_server(("127.0.0.1", 0))
        self.port = self.listener.getsockname()[1]
        self.events: list[str] = []
        self.start()

    def run(self) -> None:
        try:
            conn, _ = self.listener.accept()
            conn.settimeout(5)
            with conn:
                read_until(conn, STREAM)
                if self.crt is None:
                    conn.sendall(HEADER + SASL)
                    self.sasl(conn, "in clear")
                    return
                conn.sendall(HEADER + STARTTLS_REQUIRED)
                read_until(conn, re.compile(rb"<starttls[^>]*>"))
                self.events.append("starttls")
                conn.sendall(PROCEED)
                server = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
                server.load_cert_chain(self.crt, self.key)
                try:
                    tls = server.wrap_socket(conn, server_side=True)
                except (ssl.SSLError, OSError):
                    self.events.append("handshake refused")
                    return
                with tls:
                    read_until(tls, STREAM)
                    self.events.append("stream over TLS")
                    tls.sendall(HEADER + SASL)
                    self.sasl(tls, "over TLS")
        except (EOFError, OSError):
            pass
        finally:
            self.listener.close()

    def sasl(self, sock, how: str) -> None:
        """Refuses every login attempt (one per mechanism) until the client ends its stream."""
        end = re.compile(rb"</auth>|<auth[^>]*/>|</stream:stream>")
        buf = b""
        while True:
            buf = read_until(sock, end, buf)
            m = end.search(buf)
            if m.group() == b"</stream:stream>":
                break
            if f"auth {how}" not in self.events:
                self.events.append(f"auth {how}")
            buf = buf[m.end():]
            sock.sendall(NOT_AUTHORIZED)
        sock.sendall(b"</stream:stream>")


def run_tool(port: int, *options: str) -> tuple[int, list[str]]:
    """controlml.py's main (a get that needs no presence) against 127.0.0.1:``port``: its exit status and stderr."""
    gc.collect()  # what earlier tests left is collected now, not while stderr is the tool's
    err = io.StringIO()
    with redirect_stderr(err), mock.patch.dict(os.environ, {}, clear=False) as env:
        env.pop("SABOT_XMPP_CA", None)
        status = controlml.main(["--jid", "alice@sabot.local", "--password", "pw", "--port", str(port), "--timeout",
                                 "5", *options, "get", "robot@sabot.local/onboard", "cm.position"])
    return status, err.getvalue().splitlines()


class TlsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        d = cls.dir.name
        cls.lab = make_ca(d, "lab-ca")
        cls.other = make_ca(d, "other-ca")
        cls.crt, cls.key = make_leaf(d, cls.lab, "sabot.local")

    @classmethod
    def tearDownClass(cls):
        cls.dir.cleanup()

    def test_the_lab_ca_is_trusted_for_its_domain(self):
        handshake(controlml.ssl_context(self.lab), self.crt, self.key, "sabot.local")
        handshake(controlml.ssl_context(self.lab), self.crt, self.key, "conference.sabot.local")

    def test_another_ca_or_another_name_is_refused(self):
        with self.assertRaises(ssl.SSLCertVerificationError):
            handshake(controlml.ssl_context(self.other), self.crt, self.key, "sabot.local")
        with self.assertRaises(ssl.SSLCertVerificationError):
            handshake(controlml.ssl_context(self.lab), self.crt, self.key, "sabot2.local")

    def test_the_system_store_does_not_trust_a_lab_ca(self):
        with self.assertRaises(ssl.SSLCertVerificationError):
            handshake(controlml.ssl_context(None), self.crt, self.key, "sabot.local")

    def test_a_refusal_names_the_ca_file_and_its_fingerprint(self):
        with open(self.lab, encoding="ascii") as f:
            der = ssl.PEM_cert_to_DER_cert(f.read())
        hexdigest = hashlib.sha256(der).hexdigest().upper()
        self.assertEqual(f"the CA of {self.lab} (SHA-256 " + ":".join(hexdigest[i:i + 2] for i in range(0, 64, 2))
                         + ")", controlml.trust_description(self.lab))
        self.assertEqual("the system's trusted CAs", controlml.trust_description(None))

    def test_a_ca_file_replaces_the_system_store(self):
        # the system's store made to hold the other CA (OpenSSL reads SSL_CERT_FILE when a context loads its defaults)
        d = os.path.join(self.dir.name, "other")
        os.mkdir(d)
        crt, key = make_leaf(d, self.other, "sabot.local")
        with mock.patch.dict(os.environ, {"SSL_CERT_FILE": self.other, "SSL_CERT_DIR": d}):
            handshake(controlml.ssl_context(None), crt, key, "sabot.local")  # the system's trust, as changed
            e = refusal(controlml.ssl_context(self.lab), crt, key, "sabot.local")  # --ca-file: the lab CA only
            self.assertEqual(controlml.NOT_SIGNED & {e.verify_code}, {e.verify_code}, e)
            # what slixmpp's ca_certs does (load_verify_locations on its default context): the lab CA added to the
            # system's, which then trusts the other CA's certificate as well
            added = ssl.create_default_context()
            added.load_verify_locations(cafile=self.lab)
            handshake(added, crt, key, "sabot.local")

    def test_the_client_checks_the_certificate_and_the_domain_with_that_context(self):
        client = controlml.Client("alice@sabot.local", "pw", self.lab)
        context = client.get_ssl_context()  # what slixmpp's STARTTLS uses, with the JID's domain as server name
        self.assertIsNone(client.ca_certs)
        self.assertEqual((ssl.CERT_REQUIRED, True), (context.verify_mode, context.check_hostname))
        self.assertEqual(["lab-ca"],
                         [dict(x[0] for x in c["subject"])["commonName"] for c in context.get_ca_certs()])
        self.assertEqual("sabot.local", client.default_domain)
        self.assertFalse(client.enable_direct_tls or client.enable_plaintext)
        self.assertTrue(client.enable_starttls)
        plain = controlml.Client("alice@sabot.local", "pw", plain=True)
        self.assertEqual((False, True), (plain.enable_starttls, plain.enable_plaintext))

    def test_each_refusal_in_one_line(self):
        trust = controlml.trust_description(self.lab)
        e = refusal(controlml.ssl_context(self.other), self.crt, self.key, "sabot.local")
        self.assertEqual(f"the certificate for sabot.local is not signed by {controlml.trust_description(self.other)}",
                         controlml.tls_refusal(e, "sabot.local", controlml.trust_description(self.other)))
        e = refusal(controlml.ssl_context(self.lab), self.crt, self.key, "sabot2.local")
        self.assertEqual(f"the server's certificate does not name sabot2.local (trusted: {trust})",
                         controlml.tls_refusal(e, "sabot2.local", trust))
        d = os.path.join(self.dir.name, "expired")
        os.mkdir(d)
        crt, key = make_expired_leaf(d, self.lab, "sabot.local")
        e = refusal(controlml.ssl_context(self.lab), crt, key, "sabot.local")
        self.assertEqual(f"the certificate for sabot.local or its CA has expired (trusted: {trust})",
                         controlml.tls_refusal(e, "sabot.local", trust))
        self.assertEqual("the TLS handshake for sabot.local failed: WRONG_VERSION_NUMBER", controlml.tls_refusal(
            ssl.SSLError(1, "[SSL: WRONG_VERSION_NUMBER] wrong version number"), "sabot.local", trust)
            .replace("[SSL: WRONG_VERSION_NUMBER] wrong version number", "WRONG_VERSION_NUMBER"))

    def test_the_tool_logs_in_through_starttls_with_the_lab_ca(self):
        server = ScriptedServer(self.crt, self.key)
        status, err = run_tool(server.port, "--ca-file", self.lab)
        server.join(5)
        # the certificate was accepted: the password went over TLS only (and the scripted server refused it)
        self.assertEqual(["starttls", "stream over TLS", "auth over TLS"], server.events)
        self.assertEqual((3, [f"controlml: authentication failed (alice@sabot.local on 127.0.0.1:{server.port})"]),
                         (status, err))

    def test_the_tool_refuses_another_ca_in_one_line(self):
        server = ScriptedServer(self.crt, self.key)
        status, err = run_tool(server.port, "--ca-file", self.other)
        server.join(5)
        self.assertEqual(["starttls", "handshake refused"], server.events)
        self.assertEqual((controlml.EXIT_UNREACHABLE, [
            f"controlml: the certificate for sabot.local is not signed by {controlml.trust_description(self.other)} "
            f"(alice@sabot.local on 127.0.0.1:{server.port})"]), (status, err))

    def test_no_silent_fallback_to_a_plain_stream(self):
        server = ScriptedServer(None, None)  # no STARTTLS offered, SASL at once
        status, err = run_tool(server.port, "--ca-file", self.lab)
        server.join(5)
        self.assertEqual([], server.events)  # no login in clear
        self.assertEqual((3, ["controlml: the server offers no STARTTLS, and this client never logs in without TLS (a "
                              "server started with --tls off takes --plain) (alice@sabot.local on "
                              f"127.0.0.1:{server.port})"]), (status, err))

    def test_plain_is_refused_by_a_server_that_requires_starttls(self):
        server = ScriptedServer(self.crt, self.key)
        status, err = run_tool(server.port, "--plain")
        server.join(5)
        self.assertEqual([], server.events)
        self.assertEqual((3, ["controlml: the server requires STARTTLS (--plain is only for a server started with "
                              f"--tls off) (alice@sabot.local on 127.0.0.1:{server.port})"]), (status, err))

    def test_options(self):
        get = ["get", "r@sabot.local", "cm.position"]
        with mock.patch.dict(os.environ, {"SABOT_XMPP_CA": ""}):
            a = controlml.parse_args(["--password", "pw", "--ca-file", self.lab, *get])
            self.assertEqual((self.lab, False), (a.ca_file, a.plain))
            a = controlml.parse_args(["--password", "pw", *get])  # the system's trusted CAs
            self.assertEqual((None, False), (a.ca_file, a.plain))
            a = controlml.parse_args(["--password", "pw", "--plain", *get])
            self.assertEqual((None, True), (a.ca_file, a.plain))
        with mock.patch.dict(os.environ, {"SABOT_XMPP_CA": self.other}):
            self.assertEqual(self.other, controlml.parse_args(["--password", "pw", *get]).ca_file)
            self.assertEqual(self.lab, controlml.parse_args(["--password", "pw", "--ca-file", self.lab, *get]).ca_file)
            # given empty: the system's trusted CAs (as ServerTrust.of("") on the Java side)
            self.assertIsNone(controlml.parse_args(["--password", "pw", "--ca-file", "", *get]).ca_file)
            # --plain (a server with --tls off) is not refused for the CA that ./sabot controlml puts in the environment
            self.assertEqual((None, True), (lambda a: (a.ca_file, a.plain))(
                controlml.parse_args(["--password", "pw", "--plain", *get])))
        for wrong in (["--ca-file", self.lab, "--plain"], ["--ca-file", self.lab + ".missing"]):
            with self.assertRaises(SystemExit) as e, redirect_stderr(io.StringIO()):
                controlml.parse_args(["--password", "pw", *wrong, *get])
            self.assertEqual(controlml.EXIT_USAGE, e.exception.code)

    def test_a_ca_file_without_a_certificate_is_a_usage_error(self):
        junk = os.path.join(self.dir.name, "junk.pem")
        with open(junk, "w", encoding="ascii") as f:
            f.write("not a certificate\n")
        with self.assertRaises(controlml.Failure) as e:
            controlml.Client("alice@sabot.local", "pw", junk)
        self.assertEqual(controlml.EXIT_USAGE, e.exception.status)
        self.assertTrue(str(e.exception).startswith(f"--ca-file {junk}: "), e.exception)


if __name__ == "__main__":
    unittest.main()
