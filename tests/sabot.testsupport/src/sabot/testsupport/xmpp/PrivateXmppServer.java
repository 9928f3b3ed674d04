package sabot.testsupport.xmpp;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.lang.ProcessBuilder.Redirect;
import java.net.InetAddress;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.UUID;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.ConnectionConfiguration;
import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smack.tcp.XMPPTCPConnectionConfiguration;
import org.junit.jupiter.api.extension.AfterAllCallback;
import org.junit.jupiter.api.extension.BeforeAllCallback;
import org.junit.jupiter.api.extension.ExtensionContext;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.DomainBareJid;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.Role;
import sabot.testsupport.net.SilentRelay;
import sabot.fleet.AccessRules;
import sabot.fleet.FleetConnections;
import sabot.fleet.NoDelaySocketFactory;
import sabot.fleet.ServerTrust;

/**
 * A private XMPP server (Prosody or ejabberd) on a free loopback port, with its own configuration and state
 * directory, for one test class. Real server, real sockets: nothing is mocked.
 *
 * <pre>
 * &#64;RegisterExtension
 * static PrivateXmppServer xmpp = PrivateXmppServer.prosody();
 * ...
 * XMPPTCPConnection alice = xmpp.login("alice");   // account made by the administrator (sabot-xmpp register) on first use
 * </pre>
 *
 * The server is started, awaited and stopped by {@code product/bin/sabot-xmpp}, the script behind
 * {@code ./sabot xmpp}: one implementation of the private server for the tests, the benchmarks and the demo. Its
 * configuration is the project's own ({@code product/xmpp/}); the MAM archive is kept in memory. The system-wide
 * server is never touched. Usable outside JUnit through {@link #start()} and {@link #close()}.
 */
public final class PrivateXmppServer implements BeforeAllCallback, AfterAllCallback, AutoCloseable {

    /** The server implementations the fixture can run. */
    public enum Kind {
        PROSODY("prosody"), EJABBERD("ejabberd");

        /** The name sabot-xmpp's {@code --server} takes, also the Debian package's. */
        final String serverName;

        Kind(String serverName) {
            this.serverName = serverName;
        }
    }

    /** The first virtual host. */
    public static final String DOMAIN = "sabot.local";
    /** The second virtual host, for cross-domain exchanges. */
    public static final String SECOND_DOMAIN = "sabot2.local";
    /** Password given to accounts that the fixture creates on demand. */
    public static final String DEFAULT_PASSWORD = "sabot-test-pw";

    private static final Duration READY_TIMEOUT = Duration.ofSeconds(60);
    private static final Duration STOP_GRACE = Duration.ofSeconds(3);
    /** The script's own deadlines (ready, then stop after a failure: grace and SIGKILL) plus a margin. */
    private static final Duration SCRIPT_TIMEOUT = READY_TIMEOUT.plusSeconds(30);
    /** Where the script writes what it says (its log lines and, on failure, the server's), in the state directory. */
    private static final String SCRIPT_LOG = "sabot-xmpp.log";

    private final Kind kind;
    private final List<XMPPTCPConnection> connections = new ArrayList<>();
    /** The server's process id while it runs, else 0. */
    private long pid;
    private Path runDir;
    private int port;
    /** The lab CA that signs the server's certificates (made by sabot-xmpp in the state directory). */
    private Path caFile;
    private ServerTrust trust;
    private Duration startupTime;
    private Thread shutdownHook;
    /** Plain TCP, no TLS ({@code sabot-xmpp start --tls off}): for the benchmark that compares the two only. */
    private boolean plainTcp;
    /** The archive ({@code sabot-xmpp start --archive}): MAM in memory, or PostgreSQL ({@link #sqlArchive()}). */
    private String archive = "memory";
    /** 2 for a two-node ejabberd cluster ({@link #ejabberdCluster()}), else 1. */
    private int nodes = 1;
    /** A cluster's second node: its pid (0 when stopped), port and loopback address; or a federation's ejabberd. */
    private long pid2;
    private int port2;
    private InetAddress address2;
    /** Two domains on two servers federated over s2s ({@link #federation()}). */
    private boolean federation;
    /**
     * A federation's s2s links through relays that can go silent ({@link #federationThroughRelays()}): to ejabberd
     * and to Prosody; null otherwise. With the s2s listeners' ports, chosen once so that a restart keeps them.
     */
    private SilentRelay toEjabberd, toProsody;
    private int s2sProsody, s2sEjabberd;
    /** A federation whose ejabberd has a CA of its own ({@link #federationWithForeignPeerCa()}). */
    private boolean foreignPeerCa;
    /** Trust in the CA of a federation's ejabberd (DIR/peer/ca: the lab CA, or its own one). */
    private ServerTrust peerTrust;

    private PrivateXmppServer(Kind kind) {
        this.kind = Objects.requireNonNull(kind);
    }

    /** @return a fixture for a private Prosody (about 0.1 s to ready here) */
    public static PrivateXmppServer prosody() {
        return new PrivateXmppServer(Kind.PROSODY);
    }

    /** @return a fixture for a private ejabberd (about 1 s to ready here) */
    public static PrivateXmppServer ejabberd() {
        return new PrivateXmppServer(Kind.EJABBERD);
    }

    /**
     * @return a fixture for a private two-node ejabberd cluster (docs/CLUSTER.md): node 1 on 127.0.0.1, node 2 on
     *         127.0.0.2, one Mnesia (accounts, rosters, shared groups) and one XMPP service; about 4 s to ready here.
     *         {@link #port()} and {@link #configuration} are node 1's; {@link #configuration(int, String, String,
     *         String)} picks a node
     */
    public static PrivateXmppServer ejabberdCluster() {
        PrivateXmppServer s = new PrivateXmppServer(Kind.EJABBERD);
        s.nodes = 2;
        return s;
    }

    /**
     * @return a fixture for two domains on two servers federated over s2s (docs/FEDERATION.md): Prosody serving
     *         {@link #DOMAIN} on 127.0.0.1, ejabberd serving {@link #SECOND_DOMAIN} on 127.0.0.2, TLS and
     *         certificates of one lab CA between them; about 2 s to ready here. {@link #configuration(String, String,
     *         String)} and {@link #login(String, String)} pick the server of the domain; {@link #grant(BareJid, Role)}
     *         and {@link #enrolRobot(BareJid)} act on the server of a robot's domain through
     *         {@link #grantOn(String, BareJid, Role)}
     */
    public static PrivateXmppServer federation() {
        PrivateXmppServer s = new PrivateXmppServer(Kind.PROSODY);
        s.federation = true;
        return s;
    }

    /**
     * @return a {@link #federation()} whose s2s connections, both ways, pass through relays on loopback that
     *         {@link #partition()} silences and {@link #heal()} resumes (a dead link between the domains: nothing
     *         passes, nothing is closed)
     */
    public static PrivateXmppServer federationThroughRelays() {
        PrivateXmppServer s = federation();
        s.s2sProsody = -1; // chosen at the first start
        return s;
    }

    /**
     * @return a {@link #federation()} whose ejabberd's certificate is signed by a CA of its own, not by the lab CA
     *         that Prosody trusts (and which ejabberd trusts instead of it): s2s fails both ways
     */
    public static PrivateXmppServer federationWithForeignPeerCa() {
        PrivateXmppServer s = federation();
        s.foreignPeerCa = true;
        return s;
    }

    /** Silences the s2s link between the domains, both ways ({@link #federationThroughRelays()}). */
    public void partition() throws IOException {
        relays().forEach(SilentRelay::silence);
    }

    /** Resumes the s2s link: what was held passes on ({@link #federationThroughRelays()}). */
    public void heal() throws IOException {
        relays().forEach(SilentRelay::resume);
    }

    private interface RelayAction {
        void on(SilentRelay relay) throws IOException;
    }

    private record Relays(SilentRelay a, SilentRelay b) {
        void forEach(RelayAction action) throws IOException {
            action.on(a);
            action.on(b);
        }
    }

    private Relays relays() {
        if (toEjabberd == null) {
            throw new IllegalStateException("not a federation through relays (federationThroughRelays()), or not "
                    + "started");
        }
        return new Relays(toEjabberd, toProsody);
    }

    /** A port of {@code address} with no listener now (the script binds it a moment later). */
    private static int freePort(String address) throws IOException {
        try (java.net.ServerSocket s = new java.net.ServerSocket(0, 1, InetAddress.getByName(address))) {
            return s.getLocalPort();
        }
    }

    /**
     * Makes the server accept plain TCP streams ({@code --tls off}; set before {@link #start()}): for the benchmark
     * that compares TLS with plain TCP, never for a test of the product, whose clients require TLS.
     *
     * @return this fixture
     */
    public PrivateXmppServer plainTcp() {
        this.plainTcp = true;
        return this;
    }

    /**
     * Gives the server (ejabberd) its archive in a private PostgreSQL ({@code --archive sql}; set before
     * {@link #start()}): MAM, offline messages and entity capabilities there, and every ControlML stanza archived
     * (docs/ARCHIVE.md), read with {@link #archiveLog(String...)}.
     *
     * @return this fixture
     */
    public PrivateXmppServer sqlArchive() {
        this.archive = "sql";
        return this;
    }

    /** @return a fixture for the given server kind */
    public static PrivateXmppServer of(Kind kind) {
        return new PrivateXmppServer(kind);
    }

    @Override
    public void beforeAll(ExtensionContext context) throws Exception {
        start();
    }

    @Override
    public void afterAll(ExtensionContext context) {
        close();
    }

    /**
     * Starts the server on a free port and waits until it answers a client stream header with its stream features.
     *
     * @throws IOException when the server exits, logs a fatal error or is not ready within 60 s; the message holds
     *                     the reason and the end of the server's log, and the server is stopped
     */
    public synchronized PrivateXmppServer start() throws IOException, InterruptedException {
        return start(0);
    }

    /**
     * Starts the server on port {@code c2sPort} of 127.0.0.1 (0: a free port), as {@link #start()}: for tests of
     * what happens when the port is taken.
     */
    public synchronized PrivateXmppServer start(int c2sPort) throws IOException, InterruptedException {
        if (pid != 0) {
            return this;
        }
        runDir = repositoryRoot().resolve("target/xmpp-run/" + kind.serverName + "-" + UUID.randomUUID().toString()
                .substring(0, 8)).toAbsolutePath();
        long t0 = System.nanoTime();
        if (foreignPeerCa) { // DIR/peer/ca of its own before the first start: sabot-xmpp keeps it (and warns)
            Path ca = Files.createDirectories(runDir.resolve("peer/ca"));
            Process openssl = new ProcessBuilder("openssl", "req", "-x509", "-newkey", "ec", "-pkeyopt",
                    "ec_paramgen_curve:prime256v1", "-nodes", "-days", "30", "-subj", "/O=Elsewhere/CN=Foreign CA",
                    "-addext", "basicConstraints=critical,CA:TRUE", "-addext", "keyUsage=critical,keyCertSign,cRLSign",
                    "-keyout", ca.resolve("ca.key").toString(), "-out", ca.resolve("ca.pem").toString())
                    .redirectErrorStream(true).redirectOutput(Redirect.appendTo(runDir.resolve(SCRIPT_LOG).toFile()))
                    .start();
            openssl.getOutputStream().close();
            if (awaitScript(openssl) != 0) {
                throw new IOException("openssl made no foreign CA in " + ca + "; see " + runDir.resolve(SCRIPT_LOG));
            }
        }
        launch(c2sPort);
        startupTime = Duration.ofNanos(System.nanoTime() - t0);
        shutdownHook = new Thread(this::stopProcess, "stop-private-" + kind.serverName);
        Runtime.getRuntime().addShutdownHook(shutdownHook);
        System.out.printf("[xmpp] private %s pid %d ready on 127.0.0.1:%d%s after %d ms, dir %s%n", kind.serverName,
                pid, port, nodes == 2 ? " (cluster: node 2 pid " + pid2 + " on " + address2.getHostAddress() + ":"
                        + port2 + ")" : federation ? " for " + DOMAIN + " (federated with ejabberd for "
                                + SECOND_DOMAIN + ", pid " + pid2 + " on " + address2.getHostAddress() + ":" + port2
                                + ")" : "", startupTime.toMillis(), runDir);
        return this;
    }

    /**
     * Stops the server process but keeps its port and state directory (accounts, rosters, vCards), so that
     * {@link #restart()} brings the same server back: for tests of clients that must survive a server restart.
     * Clients see their connection closed as the server shuts down.
     */
    public synchronized void stopServer() {
        stopProcess();
    }

    /** Starts the server stopped by {@link #stopServer()} again, on the same port with the same state. */
    public synchronized PrivateXmppServer restart() throws IOException, InterruptedException {
        if (pid != 0) {
            return this;
        }
        if (runDir == null) {
            return start();
        }
        launch(port);
        System.out.printf("[xmpp] private %s pid %d restarted on 127.0.0.1:%d%n", kind.serverName, pid, port);
        return this;
    }

    /** Runs {@code sabot-xmpp start} and takes the server's pid and port from the line it prints when ready. */
    private void launch(int c2sPort) throws IOException, InterruptedException {
        Files.createDirectories(runDir);
        Path log = runDir.resolve(SCRIPT_LOG);
        List<String> arguments = new ArrayList<>(List.of("start", "--run", runDir.toString(), "--port", Integer
                .toString(c2sPort), "--archive", archive, "--timeout", Long.toString(READY_TIMEOUT.toSeconds()),
                "--tls", plainTcp ? "off" : "required"));
        arguments.addAll(federation ? List.of("--federate") : List.of("--server", kind.serverName, "--nodes", Integer
                .toString(nodes)));
        if (s2sProsody != 0) { // through relays: the listeners' ports fixed, and each server dials the other's relay
            if (toEjabberd == null) {
                s2sProsody = freePort("127.0.0.1");
                s2sEjabberd = freePort("127.0.0.2");
                toEjabberd = new SilentRelay(new java.net.InetSocketAddress(InetAddress.getByName("127.0.0.2"),
                        s2sEjabberd));
                toProsody = new SilentRelay(s2sProsody);
            }
            arguments.addAll(List.of("--s2s-ports", s2sProsody + "," + s2sEjabberd, "--s2s-via", toEjabberd.port()
                    + "," + toProsody.port()));
        }
        Process script = script(arguments.toArray(String[]::new)).redirectError(log.toFile()).start();
        script.getOutputStream().close();
        // the script exits once the server is ready or has failed (its own deadlines); the server, in its own
        // session, has its output in its state directory: nothing of it holds this pipe open
        String out = new String(script.getInputStream().readAllBytes(), StandardCharsets.UTF_8).trim();
        int status = awaitScript(script);
        if (status != 0) {
            throw new IOException("private " + kind.serverName + " did not start: " + failure(log) + "\n"
                    + tail(log));
        }
        Map<String, String> ready = new HashMap<>();
        for (String field : out.substring(out.lastIndexOf('\n') + 1).split(" ")) {
            int eq = field.indexOf('=');
            if (eq > 0) {
                ready.put(field.substring(0, eq), field.substring(eq + 1));
            }
        }
        try {
            pid = Long.parseLong(ready.get("pid"));
            port = Integer.parseInt(ready.get("port"));
            caFile = Path.of(ready.get("ca"));
            if (nodes == 2 || federation) {
                pid2 = Long.parseLong(ready.get("pid2"));
                port2 = Integer.parseInt(ready.get("port2"));
                address2 = InetAddress.getByName(ready.get("address2"));
            }
        } catch (NumberFormatException | NullPointerException e) {
            throw new IOException("sabot-xmpp start printed no 'pid=N port=N ... ca=FILE' line but '" + out
                    + "'; see " + log, e);
        }
        trust = plainTcp ? null : ServerTrust.labCa(caFile);
        if (federation) {
            peerTrust = ServerTrust.labCa(runDir.resolve("peer/ca/ca.pem"));
        }
    }

    /** The script's {@code [sabot] error:} line, the reason it gives for a failure. */
    private static String failure(Path log) {
        try {
            return Files.readAllLines(log).stream().filter(l -> l.startsWith("[sabot] error: ")).reduce((a, b) -> b)
                    .map(l -> l.substring("[sabot] error: ".length())).orElse("(no reason given; see " + log + ")");
        } catch (IOException e) {
            return "(no " + log + ")";
        }
    }

    private ProcessBuilder script(String... arguments) {
        return command("sabot-xmpp", arguments);
    }

    private ProcessBuilder command(String name, String... arguments) {
        Path script = repositoryRoot().resolve("product/bin/" + name);
        if (!Files.isExecutable(script)) {
            throw new IllegalStateException(script + " is missing or not executable");
        }
        List<String> command = new ArrayList<>();
        command.add(script.toString());
        command.addAll(List.of(arguments));
        return new ProcessBuilder(command);
    }

    private static int awaitScript(Process script) throws InterruptedException {
        if (!script.waitFor(SCRIPT_TIMEOUT.toMillis(), TimeUnit.MILLISECONDS)) {
            script.destroyForcibly();
            script.waitFor();
        }
        return script.exitValue();
    }

    private static String tail(Path file) {
        try {
            String s = Files.readString(file);
            return s.substring(Math.max(0, s.length() - 4000));
        } catch (IOException e) {
            return "(no " + file + ")";
        }
    }

    /** @return the server kind */
    public Kind kind() {
        return kind;
    }

    /** @return the c2s port on 127.0.0.1 */
    public int port() {
        return port;
    }

    /** @return the server's state directory (logs, data) */
    public Path runDir() {
        return runDir;
    }

    /** @return time from the start (sabot-xmpp start) to the first stream features */
    public Duration startupTime() {
        return startupTime;
    }

    /** @return the operating-system process id of the server */
    public long pid() {
        return pid;
    }

    /** @return the lab CA's certificate (PEM) that signs this server's certificates: what its clients trust */
    public Path caFile() {
        return caFile;
    }

    /** @return trust in this server's lab CA only; null for a {@link #plainTcp()} server */
    public ServerTrust trust() {
        return trust;
    }

    /**
     * A connection configuration for this server: loopback address (no DNS), TLS required with the server's lab CA
     * and the domain checked (as every Sabot client), TCP_NODELAY, no compression. Callers may change it before
     * {@code build()}.
     */
    public XMPPTCPConnectionConfiguration.Builder configuration(String localpart, String domain, String password) {
        if (federation && SECOND_DOMAIN.equals(domain)) { // the federation's ejabberd
            return configuration(port2, peerTrust, localpart, domain, password).setHostAddress(address2);
        }
        return configuration(port, trust, localpart, domain, password);
    }

    /**
     * As {@link #configuration(String, String, String)}, to a node of a cluster ({@link #ejabberdCluster()}).
     *
     * @param node 1 or 2
     */
    public XMPPTCPConnectionConfiguration.Builder configuration(int node, String localpart, String domain,
            String password) {
        return configuration(port(node), trust, localpart, domain, password).setHostAddress(address(node));
    }

    /** @return the client port of a node (1 or 2) of a cluster; node 1 is {@link #port()} */
    public int port(int node) {
        checkNode(node);
        return node == 1 ? port : port2;
    }

    /** @return the loopback address of a node (1: 127.0.0.1, 2: 127.0.0.2) */
    public InetAddress address(int node) {
        checkNode(node);
        return node == 1 ? InetAddress.getLoopbackAddress() : address2;
    }

    /** @return the pid of a node's server process, 0 once it was killed */
    public long pid(int node) {
        checkNode(node);
        return node == 1 ? pid : pid2;
    }

    private void checkNode(int node) {
        if (node < 1 || node > nodes) {
            throw new IllegalArgumentException("node " + node + ": this fixture has " + nodes + " node(s)");
        }
    }

    /**
     * Kills a node of a cluster at once (SIGKILL to its process group), as a crash would: its clients' connections
     * break without a closing stream; the other node goes on serving.
     */
    public synchronized void killNode(int node) throws IOException, InterruptedException {
        checkNode(node);
        long p = pid(node);
        if (p == 0) {
            return;
        }
        Process kill = new ProcessBuilder("kill", "-KILL", "--", "-" + p).redirectErrorStream(true).start();
        kill.getOutputStream().close();
        kill.waitFor();
        ProcessHandle.of(p).ifPresent(h -> h.onExit().join());
        if (node == 1) {
            pid = 0;
        } else {
            pid2 = 0;
        }
    }

    /**
     * As {@link #configuration(String, String, String)}, for a private server started by another process (its
     * loopback port and its lab CA known).
     */
    public static XMPPTCPConnectionConfiguration.Builder configuration(int port, ServerTrust trust, String localpart,
            String domain, String password) {
        try {
            XMPPTCPConnectionConfiguration.Builder b = XMPPTCPConnectionConfiguration.builder()
                    .setXmppDomain(JidCreate.domainBareFrom(domain))
                    .setHostAddress(InetAddress.getLoopbackAddress())
                    .setPort(port)
                    .setUsernameAndPassword(localpart, password)
                    .setResource("test")
                    .setSocketFactory(new NoDelaySocketFactory())
                    .setSendPresence(true)
                    .setConnectTimeout(10_000);
            if (trust == null) { // a plainTcp() server's: the benchmark's comparison only
                return b.setSecurityMode(ConnectionConfiguration.SecurityMode.disabled);
            }
            return FleetConnections.secured(b, trust);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * Makes an account as the lab's administrator does ({@code sabot-xmpp register}: in-band registration is closed).
     *
     * @throws IOException when the server refuses, e.g. the account exists ("already an account: ...")
     */
    public EntityBareJid register(String localpart, String domain, String password) throws IOException,
            InterruptedException {
        EntityBareJid jid = JidCreate.entityBareFrom(localpart + "@" + domain);
        registerAll(Map.of(jid, password));
        return jid;
    }

    /** Makes many accounts in one {@code sabot-xmpp register} (the benchmarks' fleets): JID to password. */
    public void registerAll(Map<EntityBareJid, String> accounts) throws IOException, InterruptedException {
        StringBuilder lines = new StringBuilder();
        accounts.forEach((jid, password) -> lines.append(jid).append(' ').append(password).append('\n'));
        runScript(lines.toString(), "register", "--run", runDir.toString(), "-");
    }

    /**
     * Enrols a robot as a lab does ({@code sabot-xmpp enrol token}): its account, in the quarantine group
     * ({@link AccessRules#ENROLLING_GROUP}), with a one-time token as its password.
     *
     * @return the token
     */
    public String enrolToken(BareJid robot) throws IOException, InterruptedException {
        return runScript("", "enrol", "token", "--run", runDir.toString(), robot.toString()).strip();
    }

    /** {@code sabot-xmpp enrol approve}: the robot out of the quarantine, into the lab's robots. */
    public void approve(BareJid robot) throws IOException, InterruptedException {
        runScript("", "enrol", "approve", "--run", runDir.toString(), robot.toString());
    }

    /** {@code sabot-xmpp enrol refuse}: the robot out of the quarantine and its account deleted. */
    public void refuse(BareJid robot) throws IOException, InterruptedException {
        runScript("", "enrol", "refuse", "--run", runDir.toString(), robot.toString());
    }

    /**
     * Reads the ControlML archive ({@link #sqlArchive()}) as {@code ./sabot log} does: {@code product/bin/sabot-log}
     * with this server's state directory and {@code arguments}.
     *
     * @return its lines
     * @throws IOException with its error line when it fails
     */
    public List<String> archiveLog(String... arguments) throws IOException, InterruptedException {
        List<String> command = new ArrayList<>(List.of("--run", runDir.toString()));
        command.addAll(List.of(arguments));
        String out = runCommand("sabot-log", "", command.toArray(String[]::new));
        return out.isEmpty() ? List.of() : List.of(out.split("\n"));
    }

    /**
     * The server's statistics as {@code ./sabot stats} gives them: {@code product/bin/sabot-stats} with this server's
     * state directory and {@code arguments} (docs/STATISTICS.md).
     *
     * @return its lines
     * @throws IOException with its error line when it fails
     */
    public List<String> statistics(String... arguments) throws IOException, InterruptedException {
        List<String> command = new ArrayList<>(List.of("--run", runDir.toString()));
        command.addAll(List.of(arguments));
        String out = runCommand("sabot-stats", "", command.toArray(String[]::new));
        return out.isEmpty() ? List.of() : List.of(out.split("\n"));
    }

    /**
     * Runs SQL in the archive's database ({@link #sqlArchive()}; {@code sabot-xmpp sql}).
     *
     * @return its rows, fields separated by {@code |}
     */
    public List<String> archiveSql(String sql) throws IOException, InterruptedException {
        String out = runScript(sql, "sql", "--run", runDir.toString()).strip();
        return out.isEmpty() ? List.of() : List.of(out.split("\n"));
    }

    /**
     * @return the process id of the archive's PostgreSQL ({@link #sqlArchive()}: its postmaster, whose children are
     *         the database's other processes) while it runs; empty without one
     */
    public java.util.OptionalLong archiveDatabasePid() {
        try {
            List<String> lines = Files.readAllLines(runDir.resolve("pg/data/postmaster.pid"));
            return lines.isEmpty() ? java.util.OptionalLong.empty() : java.util.OptionalLong.of(Long.parseLong(lines
                    .get(0).strip()));
        } catch (IOException | NumberFormatException | NullPointerException e) {
            return java.util.OptionalLong.empty();
        }
    }

    /** Runs sabot-xmpp with {@code input} on its stdin; its log appended to the script log. @return its stdout */
    private String runScript(String input, String... arguments) throws IOException, InterruptedException {
        return runCommand("sabot-xmpp", input, arguments);
    }

    private String runCommand(String name, String input, String... arguments) throws IOException,
            InterruptedException {
        Path log = runDir.resolve(SCRIPT_LOG);
        Process script = command(name, arguments).redirectError(Redirect.appendTo(log.toFile())).start();
        try (var in = script.getOutputStream()) {
            in.write(input.getBytes(StandardCharsets.UTF_8));
        }
        String out = new String(script.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        int status = awaitScript(script);
        if (status != 0) {
            throw new IOException(name + " " + String.join(" ", arguments) + " failed: " + failure(log));
        }
        return out;
    }

    /**
     * Grants a role on the lab's robots: puts {@code jid} into the role's shared group of the server
     * ({@link AccessRules#LAB_GROUPS}), with {@code sabot-xmpp group add}, as a lab administrator does.
     */
    public void grant(BareJid jid, Role role) throws IOException, InterruptedException {
        group("add", AccessRules.LAB_GROUPS.get(role), jid);
    }

    /**
     * Grants a role on the lab's robots of {@code domain}'s server ({@link #federation()}): the account {@code jid},
     * of this domain or the other, in the role's group there (docs/FEDERATION.md, "Roles across domains").
     */
    public void grantOn(String domain, BareJid jid, Role role) throws IOException, InterruptedException {
        runScript("", "group", "add", "--run", runDirOf(domain).toString(), AccessRules.LAB_GROUPS.get(role), jid
                .toString());
    }

    /** The state directory of the server of {@code domain}: a federation's ejabberd has its own. */
    private Path runDirOf(String domain) {
        return federation && SECOND_DOMAIN.equals(domain) ? runDir.resolve("peer") : runDir;
    }

    /** @return the log file of the server of {@code domain} ({@link #federation()}: Prosody's or ejabberd's) */
    public Path serverLog(String domain) {
        return federation && SECOND_DOMAIN.equals(domain) ? runDir.resolve("peer/logs/ejabberd.log")
                : kind == Kind.PROSODY ? runDir.resolve("prosody.log") : runDir.resolve("logs/ejabberd.log");
    }

    /** Takes a role away: {@code sabot-xmpp group remove} of the role's shared group. */
    public void revoke(BareJid jid, Role role) throws IOException, InterruptedException {
        group("remove", AccessRules.LAB_GROUPS.get(role), jid);
    }

    /** Makes {@code jid} one of the lab's robots: the shared group {@link AccessRules#ROBOTS_GROUP}. */
    public void enrolRobot(BareJid jid) throws IOException, InterruptedException {
        runScript("", "group", "add", "--run", runDirOf(jid.getDomain().toString()).toString(),
                AccessRules.ROBOTS_GROUP, jid.toString());
    }

    /** {@code sabot-xmpp group add|remove}: a shared group's change, applied to the online accounts' rosters. */
    public void group(String op, String group, BareJid jid) throws IOException, InterruptedException {
        runScript("", "group", op, "--run", runDir.toString(), group, jid.toString());
    }

    /** Makes {@code localpart@sabot.local} with the default password, connects and logs in. */
    public XMPPTCPConnection login(String localpart) throws IOException, InterruptedException, SmackException,
            XMPPException {
        return login(localpart, DOMAIN);
    }

    /** Makes {@code localpart@domain} with the default password, connects and logs in. */
    public XMPPTCPConnection login(String localpart, String domain) throws IOException, InterruptedException,
            SmackException, XMPPException {
        register(localpart, domain, DEFAULT_PASSWORD);
        return connect(configuration(localpart, domain, DEFAULT_PASSWORD).build());
    }

    /** Connects and logs in with a configuration; the connection is closed when the fixture stops. */
    public XMPPTCPConnection connect(XMPPTCPConnectionConfiguration configuration) throws IOException,
            InterruptedException, SmackException, XMPPException {
        return connect(new XMPPTCPConnection(configuration));
    }

    /**
     * Connects and logs in a connection made by the caller (who has set up its listeners and managers before the
     * login); it is closed when the fixture stops.
     */
    public XMPPTCPConnection connect(XMPPTCPConnection connection) throws IOException, InterruptedException,
            SmackException, XMPPException {
        synchronized (connections) {
            connections.add(connection);
        }
        connection.connect().login();
        return connection;
    }

    /** @return the domain as a JID */
    public static DomainBareJid domainJid(String domain) {
        try {
            return JidCreate.domainBareFrom(domain);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** Disconnects the fixture's connections and stops the server (SIGTERM, then SIGKILL after 3 s). */
    @Override
    public synchronized void close() {
        synchronized (connections) {
            for (XMPPTCPConnection c : connections) {
                if (c.isConnected()) {
                    c.instantShutdown();
                }
            }
            connections.clear();
        }
        stopProcess();
        if (toEjabberd != null) {
            toEjabberd.close();
            toProsody.close();
            toEjabberd = null;
            toProsody = null;
        }
        if (shutdownHook != null) {
            try {
                Runtime.getRuntime().removeShutdownHook(shutdownHook);
            } catch (IllegalStateException shuttingDown) {
                // the hook is running or has run
            }
            shutdownHook = null;
        }
    }

    /** Stops the server with {@code sabot-xmpp stop}: SIGTERM to its process group, SIGKILL after 3 s. */
    private void stopProcess() {
        if (pid == 0 && pid2 == 0) {
            return;
        }
        int status;
        try {
            Process stop = script("stop", "--run", runDir.toString(), "--grace", Long.toString(STOP_GRACE
                    .toSeconds())).redirectErrorStream(true).redirectOutput(Redirect.appendTo(runDir.resolve(
                            SCRIPT_LOG).toFile())).start();
            stop.getOutputStream().close();
            status = awaitScript(stop);
        } catch (IOException e) {
            throw new UncheckedIOException("could not run sabot-xmpp stop for " + runDir, e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IllegalStateException("interrupted while stopping the server of " + runDir, e);
        }
        System.out.printf("[xmpp] private %s pid %d stopped%s%n", kind.serverName, pid, status == 0 ? ""
                : ": sabot-xmpp stop failed with status " + status + ", see " + runDir.resolve(SCRIPT_LOG));
        pid = 0;
        pid2 = 0;
    }

    /** The repository root: system property {@code sabot.root}, else the nearest parent holding product/xmpp. */
    public static Path repositoryRoot() {
        String configured = System.getProperty("sabot.root");
        if (configured != null && Files.isDirectory(Paths.get(configured, "product/xmpp"))) {
            return Paths.get(configured).toAbsolutePath();
        }
        for (Path p = Paths.get("").toAbsolutePath(); p != null; p = p.getParent()) {
            if (Files.isRegularFile(p.resolve("product/xmpp/prosody.cfg.lua"))) {
                return p;
            }
        }
        throw new IllegalStateException("cannot find the Sabot repository root (product/xmpp/prosody.cfg.lua); "
                + "set -Dsabot.root");
    }
}
