package sabot.onboard.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import java.util.Arrays;
import java.util.Hashtable;
import java.util.Map;
import java.util.Set;

import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.service.component.runtime.ServiceComponentRuntime;
import org.osgi.service.metatype.MetaTypeService;
import org.osgi.util.tracker.ServiceTracker;

import sabot.modbus.Parity;
import sabot.planner.Planners;

/**
 * The Metatype descriptions generated at build time from the tasks' {@code @ObjectClassDefinition} annotations, read
 * through the real Metatype service as the onboard application reads them: every task has one, and the file check
 * refuses values outside their ranges and options, naming the key.
 */
class TaskMetatypeRangesTest {

    private static final Path FILE = Path.of("onboard.conf");
    private static Map<String, Map<String, SettingSpec>> catalog;

    @BeforeAll
    static void readCatalog() throws InterruptedException {
        BundleContext context = FrameworkUtil.getBundle(OnboardApplication.class).getBundleContext();
        catalog = OsgiTaskCatalog.read(context, service(context, ServiceComponentRuntime.class),
                service(context, MetaTypeService.class));
    }

    @Test
    void everyTaskHasItsGeneratedDescription() {
        assertEquals(Set.of("bus", "controlml", "heartbeat", "localizer", "motion", "planner", "remotefs", "teleop",
                "tracker"), catalog.keySet());
        catalog.forEach((task, settings) -> assertTrue(!settings.isEmpty(), task + " declares no setting"));
        assertEquals(13, catalog.get("localizer").size());
        assertEquals(11, catalog.get("tracker").size());
    }

    @Test
    void optionsAreTheCodesNames() {
        assertEquals(Planners.NAMES, catalog.get("planner").get("algorithm").options());
        assertEquals(Arrays.stream(Parity.values()).map(Enum::name).sorted().toList(),
                catalog.get("bus").get("parity").options().stream().sorted().toList());
    }

    @Test
    void mandatorySettingsAreThoseWithoutDefault() {
        assertTrue(catalog.get("planner").get("map").mandatory());
        assertTrue(catalog.get("remotefs").get("root").mandatory());
        assertTrue(catalog.get("controlml").get("jid").mandatory());
        assertTrue(!catalog.get("controlml").get("operators").mandatory());
        assertTrue(!catalog.get("planner").get("algorithm").mandatory());
    }

    @Test
    void valuesAtTheBoundsAreAccepted() throws Exception {
        OnboardConfigFile c = OnboardConfigFile.parse(FILE, """
                tasks = heartbeat
                heartbeat.period = 3600
                motion.rate = 5
                controlml.positionRate = 100
                remotefs.maxTransfers = 1024
                remotefs.maxChunk = 32768
                localizer.startTheta = -3.1416
                bus.parity = NONE
                planner.algorithm = lpn-focused
                tracker.controller = pseudoinverse
                """);
        Map<String, Hashtable<String, Object>> enabled = TaskSettings.resolve(c, catalog);
        assertEquals(3600, enabled.get("heartbeat").get("period"));
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "heartbeat.period = 0            | '0' is below the minimum 1",
        "heartbeat.warnLoad = 1.5        | '1.5' is above the maximum 1",
        "motion.rate = 201               | '201' is above the maximum 200",
        "motion.realtimePriority = 100   | '100' is above the maximum 99",
        "controlml.positionRate = 101    | '101' is above the maximum 100",
        "controlml.reconnectMin = 0      | '0' is below the minimum 0.001",
        "controlml.port = 65536          | '65536' is above the maximum 65535",
        "remotefs.maxTransfers = 1025    | '1025' is above the maximum 1024",
        "remotefs.maxChunk = 32769       | '32769' is above the maximum 32768",
        "remotefs.maxFileSize = -1       | '-1' is below the minimum 0",
        "bus.tcpPort = 0                 | '0' is below the minimum 1",
        "bus.interFrameDelay = 1000.5    | '1000.5' is above the maximum 1000",
        "localizer.startTheta = 3.2      | '3.2' is above the maximum 3.1416",
        "planner.threads = 3             | '3' is above the maximum 2",
        "teleop.timeout = 0.01           | '0.01' is below the minimum 0.05",
        "tracker.speedHeadroom = 1.01    | '1.01' is above the maximum 1",
        "bus.parity = MARK               | 'MARK' is not one of EVEN, NONE, ODD",
        "planner.algorithm = astar       | 'astar' is not one of lpn, lpn-bounded, lpn-focused",
        "tracker.controller = pid        | 'pid' is not one of dfl, pseudoinverse" })
    void valueOutsideItsRangeOrOptionsIsRefused(String line, String problem) throws Exception {
        OnboardConfigFile c = OnboardConfigFile.parse(FILE, "tasks = heartbeat\n" + line + "\n");
        ConfigError e = assertThrows(ConfigError.class, () -> TaskSettings.resolve(c, catalog));
        assertEquals(line.substring(0, line.indexOf(' ')), e.key(), e.getMessage());
        assertTrue(e.getMessage().contains(problem), e.getMessage());
        assertTrue(e.getMessage().contains("onboard.conf:2"), e.getMessage());
    }

    /** @return the service of that type, waited for up to 10 s */
    static <S> S service(BundleContext context, Class<S> type) throws InterruptedException {
        ServiceTracker<S, S> t = new ServiceTracker<>(context, type, null);
        t.open();
        S s = t.waitForService(10_000);
        assertNotNull(s, type.getSimpleName() + " not available");
        return s;
    }
}
