package sabot.onboard.controlml.internal.peers;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Duration;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;

import org.junit.jupiter.api.Test;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;

import sabot.fleet.AccessRules;
import sabot.onboard.task.InvalidSettings;
import sabot.onboard.task.TaskSettingsCheck;
import sabot.onboard.task.TaskSettingsCheck.Problem;
import sabot.testsupport.osgi.TaskMetatype;

/** The peers task's settings: defaults, ranges and the group, as its Metatype declares them and its check refuses. */
class PeersSettingsTest {

    final Map<String, Object> settings = new HashMap<>();

    @Test
    void defaultsApplyToEverySettingLeftOut() {
        PeersSettings s = PeersSettings.of(settings);
        assertEquals(PeersSettings.DEFAULT_RATE_HZ, s.rateHz());
        assertEquals(AccessRules.ROBOTS_GROUP, s.group(), "the server's group of the lab's robots");
    }

    @Test
    void aRateOutsideItsRangeOrNotANumberIsRefusedNamingIt() {
        for (Object bad : List.of(0.4, 20.5, Double.NaN)) {
            settings.put("rate", bad);
            assertEquals(List.of(new Problem("rate", "'" + bad + "' Hz is outside 0.5..20.0")), PeersSettings.problems(
                    settings));
        }
        settings.put("rate", "fast");
        assertEquals(List.of(new Problem("rate", "'fast' is not a number")), PeersSettings.problems(settings));
        settings.put("rate", "20");
        assertEquals(20, PeersSettings.of(settings).rateHz(), "the bound itself");
    }

    @Test
    void theGroupMustBeNamedWithoutAControlCharacter() {
        settings.put("group", " ");
        assertEquals(List.of(new Problem("group", "no group given (the server's shared group of the lab's robots, "
                + "e.g. sabot-robots)")), PeersSettings.problems(settings));
        settings.put("group", "lab\u0007robots");
        assertEquals(List.of(new Problem("group", "group name 'lab?robots' has a control character")), PeersSettings
                .problems(settings));
        settings.put("group", " lab-7-robots ");
        assertEquals("lab-7-robots", PeersSettings.of(settings).group());
    }

    @Test
    void activationWithBadSettingsFailsNamingEveryKey() {
        settings.put("rate", 100);
        settings.put("group", "");
        InvalidSettings e = assertThrows(InvalidSettings.class, () -> PeersSettings.of(settings));
        assertEquals("task 'peers' not started: key 'peers.rate': '100.0' Hz is outside 0.5..20.0; key 'peers.group': "
                + "no group given (the server's shared group of the lab's robots, e.g. sabot-robots)", e.getMessage());
    }

    @Test
    void theMetatypeDeclaresExactlyTheseSettingsWithTheirDefaults() throws Exception {
        BundleContext context = FrameworkUtil.getBundle(PeersTask.class).getBundleContext();
        Map<String, String> d = TaskMetatype.defaults(context.getBundle(), "sabot.task.peers");
        assertEquals(Set.of("rate", "group"), d.keySet());
        assertEquals(PeersSettings.DEFAULT_RATE_HZ, Double.parseDouble(d.get("rate")));
        assertEquals(AccessRules.ROBOTS_GROUP, d.get("group"));
        // the range the file is checked against before anything starts: the parse's own
        var rate = TaskMetatype.attributes(context.getBundle(), "sabot.task.peers").get("rate");
        for (double ok : new double[] { PeersSettings.MIN_RATE_HZ, PeersSettings.MAX_RATE_HZ }) {
            assertEquals("", rate.validate(Double.toString(ok)), "rate " + ok);
        }
        for (double bad : new double[] { PeersSettings.MIN_RATE_HZ - 0.1, PeersSettings.MAX_RATE_HZ + 0.1 }) {
            assertTrue(!rate.validate(Double.toString(bad)).isEmpty(), "rate " + bad + " accepted");
        }
    }

    @Test
    void theSettingsCheckIsRegisteredForTheTask() throws Exception {
        BundleContext context = FrameworkUtil.getBundle(PeersTask.class).getBundleContext();
        var refs = context.getServiceReferences(TaskSettingsCheck.class, "(" + TaskSettingsCheck.TASK + "=peers)");
        assertEquals(1, refs.size());
        List<Problem> problems = context.getService(refs.iterator().next()).check(Map.of("rate", 50.0));
        assertTrue(problems.stream().anyMatch(p -> p.setting().equals("rate")), problems::toString);
    }

    @Test
    void aFailedSubscriptionIsAskedForAgainAfterADelayThatDoublesUpToItsMaximum() {
        assertEquals(List.of(1L, 2L, 4L, 8L, 16L, 30L, 30L), List.of(1, 2, 3, 4, 5, 6, 40).stream().map(
                n -> PeersTask.retryDelay(n).toSeconds()).toList());
        assertEquals(Duration.ofSeconds(30), PeersTask.SUBSCRIBE_RETRY_MAX);
    }
}
