"""controlml.py's TLS: the client trusts the CA of --ca-file only and checks the host name; a certificate from
another CA is refused. A TLS handshake on a loopback socket inside the test (no XMPP server), with certificates that
openssl makes the way product/bin/sabot-xmpp makes the lab CA's."""

import os
import socket
import ssl
import subprocess
import sys
import tempfile
import threading
import unittest

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
        der = ssl.PEM_cert_to_DER_cert(open(self.lab, encoding="ascii").read())
        import hashlib
        hexdigest = hashlib.sha256(der).hexdigest().upper()
        self.assertEqual(f"the CA of {self.lab} (SHA-256 " + ":".join(hexdigest[i:i + 2] for i in range(0, 64, 2))
                         + ")", controlml.trust_description(self.lab))
        self.assertEqual("the system's trusted CAs", controlml.trust_description(None))

    def test_options(self):
        a = controlml.parse_args(["--password", "pw", "--ca-file", self.lab, "get", "r@sabot.local", "cm.position"])
        self.assertEqual((self.lab, False), (a.ca_file, a.plain))
        with self.assertRaises(SystemExit):
            controlml.parse_args(["--password", "pw", "--ca-file", self.lab, "--plain", "get", "r@sabot.local",
                                  "cm.position"])
        with self.assertRaises(SystemExit):
            controlml.parse_args(["--password", "pw", "--ca-file", self.lab + ".missing", "get", "r@sabot.local",
                                  "cm.position"])


if __name__ == "__main__":
    unittest.main()
