package sabot.onboard.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
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

/**
 * The Metatype descriptions generated at build time from the tasks' {@code @ObjectClassDefinition} annotations, read
 * through the real Metatype service as the onboard application reads them: every task has one, and the file check
 * refuses values outside their ranges and options, naming the key. The motion tasks' own ranges and options are tested
 * with their bundle (sabot.onboard.motion.tests).
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
        assertEquals(Set.of("bus", "controlml", "heartbeat", "localizer", "motion", "peers", "planner", "portal", "remotefs",
                "teleop", "tracker"), catalog.keySet());
        catalog.forEach((task, settings) -> assertTrue(!settings.isEmpty(), task + " declares no setting"));
    }

    @Test
    void mandatorySettingsAreThoseWithoutDefault() {
        assertTrue(catalog.get("remotefs").get("root").mandatory());
        assertTrue(catalog.get("controlml").get("jid").mandatory());
        assertTrue(!catalog.get("controlml").get("operatorGroups").mandatory());
    }

    @Test
    void valuesAtTheBoundsAreAccepted() throws Exception {
        OnboardConfigFile c = OnboardConfigFile.parse(FILE, """
                tasks = heartbeat
                heartbeat.period = 3600
                controlml.positionRate = 100
                remotefs.maxTransfers = 1024
                remotefs.maxChunk = 32768
                peers.rate = 20
                """);
        Map<String, Hashtable<String, Object>> enabled = TaskSettings.resolve(c, catalog);
        assertEquals(3600, enabled.get("heartbeat").get("period"));
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "heartbeat.period = 0            | '0' is below the minimum 1",
        "heartbeat.warnLoad = 1.5        | '1.5' is above the maximum 1",
        "controlml.positionRate = 101    | '101' is above the maximum 100",
        "controlml.reconnectMin = 0      | '0' is below the minimum 0.001",
        "controlml.port = 65536          | '65536' is above the maximum 65535",
        "remotefs.maxTransfers = 1025    | '1025' is above the maximum 1024",
        "remotefs.maxChunk = 32769       | '32769' is above the maximum 32768",
        "remotefs.maxFileSize = -1       | '-1' is below the minimum 0",
        "peers.rate = 0.4                | '0.4' is below the minimum 0.5",
        "peers.rate = 21                 | '21' is above the maximum 20" })
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
