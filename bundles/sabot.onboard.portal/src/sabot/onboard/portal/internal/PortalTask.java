package sabot.onboard.portal.internal;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.BindException;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.URI;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.nio.file.attribute.PosixFilePermissions;
import java.security.GeneralSecurityException;
import java.security.SecureRandom;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.HexFormat;
import java.util.Hashtable;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;

import jakarta.servlet.Servlet;

import org.jivesoftware.smackx.vcardtemp.VCardManager;
import org.jivesoftware.smackx.vcardtemp.packet.VCard;
import org.jxmpp.jid.impl.JidCreate;
import org.osgi.framework.BundleContext;
import org.osgi.framework.Constants;
import org.osgi.framework.InvalidSyntaxException;
import org.osgi.framework.ServiceReference;
import org.osgi.framework.ServiceRegistration;
import org.osgi.service.cm.Configuration;
import org.osgi.service.cm.ConfigurationAdmin;
import org.osgi.service.component.ComponentConstants;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.osgi.service.component.annotations.Reference;
import org.osgi.service.component.annotations.ReferenceCardinality;
import org.osgi.service.component.annotations.ReferencePolicy;
import org.osgi.service.metatype.annotations.Designate;
import org.osgi.service.servlet.runtime.HttpServiceRuntime;
import org.osgi.service.servlet.runtime.dto.FailedServletDTO;
import org.osgi.service.servlet.runtime.dto.RuntimeDTO;
import org.osgi.service.servlet.runtime.dto.ServletContextDTO;
import org.osgi.service.servlet.runtime.dto.ServletDTO;
import org.osgi.service.servlet.whiteboard.HttpWhiteboardConstants;
import org.osgi.util.tracker.ServiceTracker;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.Role;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.PoseEstimate;
import sabot.onboard.config.OnboardSettings;
import sabot.model.robot.BatteryState;
import sabot.onboard.robot.CommandRefused;
import sabot.onboard.robot.RobotMotion;
import sabot.onboard.session.RobotSession;
import sabot.onboard.task.OnboardTask;

/**
 * The {@code portal} task: the robot's own web page, a servlet ({@link PortalRoutes}) on the Jakarta Servlet
 * Whiteboard of Apache Felix HTTP Jetty (an embedded Jetty 11), over HTTPS when configured. The task owns the HTTP
 * service's configuration (PID {@value #HTTP_PID}): at activation it opens Jetty on its address and port (TLS from its
 * PEM files, put into a PKCS #12 key store in the bundle's data area for Jetty), and at deactivation it closes it again
 * (the product keeps Jetty closed without the portal). Status for every role, the configuration file's settings for
 * maintainers; log-in with the robot's XMPP accounts, roles by the robot's ControlML access rules
 * ({@link RobotSession#controlMl()}'s policy). Its {@link #page()} is the robot's vCard URL. Settings:
 * {@link PortalSettings.Config}, checked by {@link PortalSettingsCheck}.
 */
@Designate(ocd = PortalSettings.Config.class, factory = false)
@Component(name = "sabot.task.portal", configurationPolicy = ConfigurationPolicy.REQUIRE, immediate = true,
        service = OnboardTask.class)
public final class PortalTask implements OnboardTask, PortalRobot {

    private static final Logger LOG = LoggerFactory.getLogger(PortalTask.class);

    /** The Felix HTTP service's configuration PID (Jetty's address, port, TLS and limits). */
    static final String HTTP_PID = "org.apache.felix.http";
    /**
     * The property naming this activation on the HTTP runtime (Felix copies {@code org.apache.felix.http.runtime.init.*}
     * onto the runtime's service): the servlet is registered with that runtime only.
     */
    static final String RUNTIME_MARK = "sabot.portal";
    /** The most threads Jetty may use (an acceptor, a selector and those answering requests). */
    static final int THREADS = 8;
    /** How long a connection may stay silent (Jetty's idle timeout). */
    static final Duration IDLE_TIMEOUT = Duration.ofSeconds(30);
    /** How long the HTTP runtime may take to open after its configuration. */
    static final Duration START_TIMEOUT = Duration.ofSeconds(15);
    /** How long the QR inventory read back from the robot's vCard is kept. */
    static final Duration QR_TTL = Duration.ofSeconds(60);

    private final PortalSettings settings;
    private final RobotSession session;
    private final OnboardSettings file;
    private final ConfigurationAdmin configAdmin;
    private final List<OnboardTask> tasks = new CopyOnWriteArrayList<>();
    private volatile RobotMotion motion;
    private final Path keyStore;
    private final ServiceRegistration<Servlet> servlet;
    private final RecentLog log;
    private final URI page;
    private final Object qrLock = new Object();
    private byte[] qr;
    private long qrRead = Long.MIN_VALUE;

    @Activate
    public PortalTask(@Reference RobotSession session, @Reference OnboardSettings file,
            @Reference ConfigurationAdmin configAdmin, BundleContext context, Map<String, Object> properties)
            throws IOException {
        this.settings = PortalSettings.of(properties);
        this.session = session;
        this.file = file;
        this.configAdmin = configAdmin;
        InetSocketAddress address = new InetSocketAddress(settings.bind(), settings.port());
        try (ServerSocket probe = new ServerSocket()) { // a clear reason now, rather than Jetty's log line later
            probe.setReuseAddress(true);
            probe.bind(address);
        } catch (BindException e) {
            throw new IOException("the page cannot listen on " + settings.bind().getHostAddress() + ":" + settings
                    .port() + ": " + e.getMessage() + " (portal.port is in use, or portal.bind is not this computer's)",
                    e);
        }
        String mark = HexFormat.of().formatHex(new SecureRandom().generateSeed(8));
        Hashtable<String, Object> http = new Hashtable<>();
        http.put(OnboardTask.TASK_PROPERTY, PortalSettings.TASK);
        http.put("org.apache.felix.http.host", settings.bind().getHostAddress());
        http.put("org.apache.felix.http.enable", settings.tls() == null);
        http.put("org.apache.felix.https.enable", settings.tls() != null);
        http.put("org.apache.felix.http.timeout", (int) IDLE_TIMEOUT.toMillis());
        http.put("org.apache.felix.http.jetty.threadpool.max", THREADS);
        http.put("org.apache.felix.http.jetty.acceptors", 1);
        http.put("org.apache.felix.http.jetty.selectors", 1);
        http.put("org.apache.felix.http.jetty.sendServerHeader", false);
        http.put("org.apache.felix.http.runtime.init." + RUNTIME_MARK, mark);
        if (settings.tls() != null) {
            keyStore = writeKeyStore(context, settings.tls(), mark, http);
            http.put("org.osgi.service.http.port.secure", settings.port());
        } else {
            keyStore = null;
            http.put("org.osgi.service.http.port", settings.port());
        }
        Configuration jetty = configAdmin.getConfiguration(HTTP_PID, "?");
        jetty.update(http);
        this.log = RecentLog.attach();
        try {
            awaitRuntime(context, mark);
            Hashtable<String, Object> props = new Hashtable<>();
            props.put(HttpWhiteboardConstants.HTTP_WHITEBOARD_SERVLET_NAME, "sabot-portal");
            props.put(HttpWhiteboardConstants.HTTP_WHITEBOARD_SERVLET_PATTERN, "/*");
            props.put(HttpWhiteboardConstants.HTTP_WHITEBOARD_SERVLET_ASYNC_SUPPORTED, true);
            props.put(HttpWhiteboardConstants.HTTP_WHITEBOARD_TARGET, "(" + RUNTIME_MARK + "=" + mark + ")");
            servlet = context.registerService(Servlet.class, new PortalRoutes(this, new PortalSessions(settings
                    .sessionTimeout(), System::nanoTime), new LoginThrottle(settings.throttle(), System::nanoTime),
                    settings.tls() != null, settings.poll(), settings.requestTimeout(), assets()), props);
            awaitServed(context, mark, (Long) servlet.getReference().getProperty(Constants.SERVICE_ID));
        } catch (IOException | RuntimeException e) {
            close(null);
            throw e;
        }
        page = URI.create(settings.url());
        LOG.info("portal task started: the robot's page at {} (listening on {}:{}, {}; Jetty through the Servlet "
                + "Whiteboard)", page, settings.bind().getHostAddress(), settings.port(), settings.tls() != null
                        ? "HTTPS with " + settings.tls().certificate() : "plain HTTP: for a closed network only");
    }

    /**
     * Writes the page's TLS identity as a PKCS #12 store for Jetty, readable by this user only, with a new random
     * password, and puts its place and password into the HTTP configuration.
     */
    private static Path writeKeyStore(BundleContext context, PemIdentity.Files tls, String mark,
            Hashtable<String, Object> http) throws IOException {
        Path dir = context.getDataFile("").toPath();
        try (var old = Files.newDirectoryStream(dir, "portal-*.p12")) { // left by a process that was killed
            for (Path p : old) {
                Files.deleteIfExists(p);
            }
        }
        Path store = dir.resolve("portal-" + mark + ".p12");
        char[] password = HexFormat.of().formatHex(new SecureRandom().generateSeed(16)).toCharArray();
        Files.createFile(store, PosixFilePermissions.asFileAttribute(PosixFilePermissions.fromString("rw-------")));
        try (OutputStream out = Files.newOutputStream(store, StandardOpenOption.TRUNCATE_EXISTING)) {
            PemIdentity.keyStore(tls, password).store(out, password);
        } catch (GeneralSecurityException e) {
            Files.deleteIfExists(store);
            throw new IOException("HTTPS: " + e.getMessage(), e);
        }
        http.put("org.apache.felix.https.keystore", store.toString());
        http.put("org.apache.felix.https.keystore.type", "PKCS12");
        http.put("org.apache.felix.https.keystore.password", new String(password));
        http.put("org.apache.felix.https.keystore.key.password", new String(password));
        return store;
    }

    /** Waits for the HTTP runtime this activation configured (its mark) to be up. */
    private static void awaitRuntime(BundleContext context, String mark) throws IOException {
        ServiceTracker<HttpServiceRuntime, HttpServiceRuntime> runtime;
        try {
            runtime = new ServiceTracker<>(context, context.createFilter("(&(" + Constants.OBJECTCLASS + "="
                    + HttpServiceRuntime.class.getName() + ")(" + RUNTIME_MARK + "=" + mark + "))"), null);
        } catch (InvalidSyntaxException e) {
            throw new IllegalStateException(e);
        }
        runtime.open();
        try {
            if (runtime.waitForService(START_TIMEOUT.toMillis()) == null) {
                throw new IOException("the HTTP service (Felix Jetty) did not open within " + START_TIMEOUT
                        .toSeconds() + " s: see its log lines above");
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while the HTTP service opened", e);
        } finally {
            runtime.close();
        }
    }

    /**
     * Waits until the runtime's description says it serves the servlet, or says why not. The whiteboard takes the
     * servlet on its own thread and then changes the runtime's {@code service.changecount} (at once: the product sets
     * {@code org.apache.felix.http.whiteboard.changecount.delay = 0}), so each change of the runtime's service is a
     * moment to look again.
     */
    private static void awaitServed(BundleContext context, String mark, long servletId) throws IOException {
        String filter = "(&(" + Constants.OBJECTCLASS + "=" + HttpServiceRuntime.class.getName() + ")(" + RUNTIME_MARK
                + "=" + mark + "))";
        long[] changes = { 0 };
        org.osgi.framework.ServiceListener listener = event -> {
            synchronized (changes) {
                changes[0]++;
                changes.notifyAll();
            }
        };
        try {
            context.addServiceListener(listener, filter);
        } catch (InvalidSyntaxException e) {
            throw new IllegalStateException(e);
        }
        try {
            long deadline = System.nanoTime() + START_TIMEOUT.toNanos();
            while (true) {
                long seen;
                synchronized (changes) {
                    seen = changes[0];
                }
                String state = served(context, filter, servletId);
                if (state == null) {
                    return;
                }
                synchronized (changes) {
                    long left = deadline - System.nanoTime();
                    if (changes[0] == seen) {
                        if (left <= 0) {
                            throw new IOException(state + " within " + START_TIMEOUT.toSeconds() + " s");
                        }
                        changes.wait(Math.max(1, TimeUnit.NANOSECONDS.toMillis(left)));
                    }
                }
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while the HTTP service took the page", e);
        } finally {
            context.removeServiceListener(listener);
        }
    }

    /** @return null when the runtime serves the servlet, else why not */
    private static String served(BundleContext context, String filter, long servletId) throws IOException {
        ServiceReference<?>[] refs;
        try {
            refs = context.getServiceReferences((String) null, filter);
        } catch (InvalidSyntaxException e) {
            throw new IllegalStateException(e);
        }
        if (refs == null) {
            return "the HTTP service closed again";
        }
        HttpServiceRuntime runtime = (HttpServiceRuntime) context.getService(refs[0]);
        try {
            RuntimeDTO dto = runtime.getRuntimeDTO();
            for (FailedServletDTO failed : dto.failedServletDTOs) {
                if (failed.serviceId == servletId) {
                    throw new IOException("the HTTP service refused the page's servlet (Servlet Whiteboard failure "
                            + "reason " + failed.failureReason + ")");
                }
            }
            for (ServletContextDTO c : dto.servletContextDTOs) {
                for (ServletDTO s : c.servletDTOs) {
                    if (s.serviceId == servletId) {
                        return null;
                    }
                }
            }
            return "the HTTP service did not take the page's servlet";
        } finally {
            context.ungetService(refs[0]);
        }
    }

    @Deactivate
    void deactivate() {
        close(servlet);
        LOG.info("portal task stopped: {} no longer served", page);
    }

    /** Withdraws the servlet, closes Jetty again and deletes the key store. */
    private void close(ServiceRegistration<Servlet> registration) {
        if (registration != null) {
            try {
                registration.unregister();
            } catch (IllegalStateException gone) {
                // the bundle is stopping: the framework has withdrawn it
            }
        }
        try {
            Configuration[] mine = configAdmin.listConfigurations("(&(" + Constants.SERVICE_PID + "=" + HTTP_PID
                    + ")(" + OnboardTask.TASK_PROPERTY + "=" + PortalSettings.TASK + "))");
            if (mine != null) {
                for (Configuration c : mine) {
                    c.delete();
                }
            }
        } catch (IOException | InvalidSyntaxException | IllegalStateException e) {
            LOG.warn("portal: the HTTP service's configuration could not be removed: {}", e.toString());
        }
        if (keyStore != null) {
            try {
                Files.deleteIfExists(keyStore);
            } catch (IOException e) {
                LOG.warn("portal: {} could not be deleted: {}", keyStore, e.toString());
            }
        }
        if (log != null) {
            log.detach();
        }
    }

    @Reference(cardinality = ReferenceCardinality.OPTIONAL, policy = ReferencePolicy.DYNAMIC)
    void bindMotion(RobotMotion m) {
        motion = m;
    }

    void unbindMotion(RobotMotion m) {
        if (motion == m) {
            motion = null;
        }
    }

    /** The other tasks (not this one: a component that references its own service is a circle for SCR). */
    @Reference(cardinality = ReferenceCardinality.MULTIPLE, policy = ReferencePolicy.DYNAMIC, target = "(!("
            + ComponentConstants.COMPONENT_NAME + "=" + OnboardTask.PID_PREFIX + PortalSettings.TASK + "))")
    void bindTask(OnboardTask task) {
        tasks.add(task);
    }

    void unbindTask(OnboardTask task) {
        tasks.remove(task);
    }

    private static Map<String, byte[]> assets() throws IOException {
        Map<String, byte[]> assets = new LinkedHashMap<>();
        for (String name : new String[] { "portal.css", "portal.js" }) {
            try (InputStream in = PortalTask.class.getResourceAsStream("/web/" + name)) {
                if (in == null) {
                    throw new IOException("web/" + name + " is missing from the bundle");
                }
                assets.put("/static/" + name, in.readAllBytes());
            }
        }
        return assets;
    }

    // ------------------------------------------------------------------------------------------ OnboardTask

    @Override
    public String name() {
        return PortalSettings.TASK;
    }

    @Override
    public String status() {
        return "serving " + page;
    }

    @Override
    public Optional<URI> page() {
        return Optional.of(page);
    }

    // ------------------------------------------------------------------------------------------ PortalRobot

    @Override
    public Map<String, Object> robotState() {
        Map<String, Object> s = new LinkedHashMap<>();
        s.put("time", Instant.now().toString());
        s.put("robot", file.robotName());
        s.put("jid", session.jid());
        s.put("uuid", sabot.identity.DeviceUrn.urnOf(session.jid()));
        s.put("page", page.toString());
        s.put("online", session.isOnline());
        s.put("presence", Map.of("level", session.presenceLevel().attribute(), "reason", session.presenceReason()));
        RobotMotion m = motion;
        if (m != null) {
            PoseEstimate pose = m.pose();
            Map<String, Object> p = new LinkedHashMap<>();
            p.put("x", pose.pose().x());
            p.put("y", pose.pose().y());
            p.put("theta", pose.pose().theta());
            p.put("time", pose.time().toString());
            s.put("pose", p);
            var twist = m.velocity().twist();
            s.put("velocity", Map.of("linear", twist.linear(), "angular", twist.angular()));
            MissionStatus mission = m.mission();
            Map<String, Object> missionState = new LinkedHashMap<>();
            missionState.put("state", mission.state().name().toLowerCase(java.util.Locale.ROOT));
            missionState.put("maintenance", mission.maintenance());
            missionState.put("progress", mission.progress());
            missionState.put("detail", mission.detail() == null ? "" : mission.detail());
            List<Object> targets = new ArrayList<>(); // a mission of several targets: each with its state
            for (var target : mission.targets()) {
                Map<String, Object> one = new LinkedHashMap<>();
                one.put("x", target.goal().pose().x());
                one.put("y", target.goal().pose().y());
                one.put("action", target.action().code());
                one.put("state", target.state().code());
                targets.add(one);
            }
            missionState.put("targets", targets);
            s.put("mission", missionState);
            s.put("goal", m.goal().map(g -> (Object) Map.of("x", g.pose().x(), "y", g.pose().y(), "theta", g.pose()
                    .theta())).orElse(null));
            List<Object> path = new ArrayList<>();
            var points = m.trajectory().points();
            int step = Math.max(1, points.size() / 100);
            for (int i = 0; i < points.size(); i += step) {
                path.add(List.of(points.get(i).x(), points.get(i).y()));
            }
            s.put("path", path);
            s.put("battery", battery(m));
        }
        List<Object> states = new ArrayList<>();
        java.util.stream.Stream.concat(tasks.stream(), java.util.stream.Stream.of(this)).sorted(java.util.Comparator.comparing(OnboardTask::name)).forEach(t -> {
            String state;
            try {
                state = t.status();
            } catch (RuntimeException e) {
                state = "status unknown: " + e;
            }
            states.add(Map.of("name", t.name(), "status", state));
        });
        s.put("tasks", states);
        s.put("log", log == null ? List.of() : log.lines());
        return s;
    }

    /** @return the battery as the power board last measured it, or its fault ({@code fault}: the reason) */
    private static Map<String, Object> battery(RobotMotion m) {
        Map<String, Object> b = new LinkedHashMap<>();
        try {
            BatteryState s = m.battery();
            b.put("stateOfCharge", s.stateOfCharge());
            b.put("voltage", s.voltage());
            b.put("current", s.current());
            b.put("docked", s.docked());
            b.put("charging", s.charging());
            b.put("full", s.full());
            b.put("measured", s.measured().toString());
        } catch (CommandRefused e) {
            b.put("fault", e.getMessage());
        }
        return b;
    }

    @Override
    public Optional<GridMap> map() {
        RobotMotion m = motion;
        return m == null ? Optional.empty() : Optional.of(m.map());
    }

    @Override
    public Optional<byte[]> inventoryQr() {
        synchronized (qrLock) {
            long now = System.nanoTime();
            if (qr != null && now - qrRead < QR_TTL.toNanos()) {
                return Optional.of(qr);
            }
            if (!session.isOnline()) {
                return Optional.ofNullable(qr);
            }
            try {
                VCard card = VCardManager.getInstanceFor(session.connection()).loadVCard(JidCreate.entityBareFrom(
                        session.jid()));
                byte[] png = card.getAvatar();
                if (png != null && png.length > 0) {
                    qr = png;
                    qrRead = now;
                }
            } catch (Exception e) { // Smack's checked exceptions and a closed connection: the page shows none
                LOG.debug("portal: the robot's vCard could not be read: {}", e.toString());
            }
            return Optional.ofNullable(qr);
        }
    }

    @Override
    public Role roleOf(String account) {
        try {
            return session.controlMl().accessPolicy().roleOf(JidCreate.bareFrom(account));
        } catch (org.jxmpp.stringprep.XmppStringprepException | RuntimeException e) {
            return Role.NONE;
        }
    }

    @Override
    public boolean checkPassword(String account, String password) throws IOException {
        return session.checkPassword(account, password);
    }

    @Override
    public OnboardSettings settings() {
        return file;
    }
}
