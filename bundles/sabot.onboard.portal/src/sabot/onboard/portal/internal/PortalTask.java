package sabot.onboard.portal.internal;

import java.io.IOException;
import java.io.InputStream;
import java.net.InetSocketAddress;
import java.net.URI;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.TimeUnit;

import javax.net.ssl.SSLContext;

import org.jivesoftware.smackx.vcardtemp.VCardManager;
import org.jivesoftware.smackx.vcardtemp.packet.VCard;
import org.jxmpp.jid.impl.JidCreate;
import org.osgi.service.component.ComponentConstants;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.osgi.service.component.annotations.Reference;
import org.osgi.service.component.annotations.ReferenceCardinality;
import org.osgi.service.component.annotations.ReferencePolicy;
import org.osgi.service.metatype.annotations.Designate;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import com.sun.net.httpserver.HttpServer;
import com.sun.net.httpserver.HttpsConfigurator;
import com.sun.net.httpserver.HttpsServer;

import sabot.controlml.Role;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.PoseEstimate;
import sabot.onboard.config.OnboardSettings;
import sabot.onboard.robot.RobotMotion;
import sabot.onboard.session.RobotSession;
import sabot.onboard.task.NamedThreads;
import sabot.onboard.task.OnboardTask;

/**
 * The {@code portal} task: the robot's own web page, served by the JDK's HTTP server ({@code com.sun.net.httpserver},
 * module {@code jdk.httpserver}) on a pool of {@value #THREADS} threads {@code sabot-portal}, over HTTPS when
 * configured. Status for every role, the configuration file's settings for maintainers; log-in with the robot's XMPP
 * accounts, roles by the robot's ControlML access rules ({@link RobotSession#controlMl()}'s policy). Its
 * {@link #page()} is the robot's vCard URL. Settings: {@link PortalSettings.Config}, checked by
 * {@link PortalSettingsCheck}; requests: {@link PortalRoutes}.
 */
@Designate(ocd = PortalSettings.Config.class, factory = false)
@Component(name = "sabot.task.portal", configurationPolicy = ConfigurationPolicy.REQUIRE, immediate = true,
        service = OnboardTask.class)
public final class PortalTask implements OnboardTask, PortalRobot {

    private static final Logger LOG = LoggerFactory.getLogger(PortalTask.class);

    /** Threads answering requests: a page, its status polls and a log-in at once for a few people. */
    static final int THREADS = 4;
    /** How long the QR inventory read back from the robot's vCard is kept. */
    static final Duration QR_TTL = Duration.ofSeconds(60);
    /** How long a stop waits for requests under way. */
    static final int STOP_DELAY_S = 1;

    private final PortalSettings settings;
    private final RobotSession session;
    private final OnboardSettings file;
    private final List<OnboardTask> tasks = new CopyOnWriteArrayList<>();
    private volatile RobotMotion motion;
    private final HttpServer server;
    private final ExecutorService pool;
    private final RecentLog log;
    private final URI page;
    private final Object qrLock = new Object();
    private byte[] qr;
    private long qrRead = Long.MIN_VALUE;

    @Activate
    public PortalTask(@Reference RobotSession session, @Reference OnboardSettings file, Map<String, Object> properties)
            throws IOException {
        this.settings = PortalSettings.of(properties);
        this.session = session;
        this.file = file;
        this.log = RecentLog.attach();
        InetSocketAddress address = new InetSocketAddress(settings.bind(), settings.port());
        if (settings.tls() != null) {
            SSLContext tls;
            try {
                tls = PemIdentity.load(settings.tls());
            } catch (java.security.GeneralSecurityException e) {
                throw new IOException("HTTPS: " + e.getMessage(), e);
            }
            HttpsServer https = HttpsServer.create(address, 32);
            https.setHttpsConfigurator(new HttpsConfigurator(tls));
            server = https;
        } else {
            server = HttpServer.create(address, 32);
        }
        pool = Executors.newFixedThreadPool(THREADS, NamedThreads.daemon("sabot-portal"));
        server.setExecutor(pool);
        server.createContext("/", new PortalRoutes(this, new PortalSessions(settings.sessionTimeout(),
                System::nanoTime), new LoginThrottle(settings.throttle(), System::nanoTime), settings.tls() != null,
                settings.poll(), assets()));
        server.start();
        page = URI.create(settings.url());
        LOG.info("portal task started: the robot's page at {} (listening on {}:{}, {})", page, settings.bind()
                .getHostAddress(), server.getAddress().getPort(), settings.tls() != null ? "HTTPS with "
                        + settings.tls().certificate() : "plain HTTP: for a closed network only");
    }

    @Deactivate
    void deactivate() {
        server.stop(STOP_DELAY_S);
        pool.shutdownNow();
        try {
            pool.awaitTermination(2, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        if (log != null) {
            log.detach();
        }
        LOG.info("portal task stopped: {} no longer served", page);
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
            s.put("mission", Map.of("state", mission.state().name().toLowerCase(java.util.Locale.ROOT), "maintenance",
                    mission.maintenance(), "progress", mission.progress(), "detail", mission.detail() == null ? ""
                            : mission.detail()));
            s.put("goal", m.goal().map(g -> (Object) Map.of("x", g.pose().x(), "y", g.pose().y(), "theta", g.pose()
                    .theta())).orElse(null));
            List<Object> path = new ArrayList<>();
            var points = m.trajectory().points();
            int step = Math.max(1, points.size() / 100);
            for (int i = 0; i < points.size(); i += step) {
                path.add(List.of(points.get(i).x(), points.get(i).y()));
            }
            s.put("path", path);
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
