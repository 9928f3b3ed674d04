package sabot.tools.simulate;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.tools.CommandRun;

/**
 * {@code sabot simulate --scenario goal}: the robot's own control loop from the command line (the JSON last line,
 * the CSV and plots), and one clear error line with exit status 2 for options that do not apply to it.
 */
class SimulateCommandTest {

    @TempDir
    Path folder;

    private static CommandRun run(String... args) {
        return CommandRun.of(SimulateCommand::run, args);
    }

    /** @return the number {@code key} holds in the run's JSON line */
    private static double number(CommandRun r, String key) {
        Matcher m = Pattern.compile("\"" + key + "\":([-0-9.eE+]+)").matcher(r.lastLine());
        assertTrue(m.find(), key + " missing in " + r.lastLine());
        return Double.parseDouble(m.group(1));
    }

    @Test
    void theRobotsLoopReachesTheReferenceGoalAndWritesItsTrace() throws Exception {
        CommandRun r = run("--scenario", "goal", "--seed", "1", "--out", folder.toString());
        assertEquals(0, r.status(), r.err());
        assertTrue(r.lastLine().startsWith("{\"scenario\":\"goal\",\"loop\":\"onboard\",\"seed\":1,"
                + "\"slip_noise\":0.0100000,\"slip_bias\":0.00200000,\"mission\":\"done\""), r.lastLine());
        assertTrue(number(r, "final_m") <= 0.05, r.lastLine());
        assertEquals(0, number(r, "limit_violations"), r.lastLine());
        for (String file : new String[] { "motion-goal-onboard.csv", "motion-goal-onboard-path.png",
                "motion-goal-onboard-error.png" }) {
            assertTrue(Files.size(folder.resolve(file)) > 0, file);
        }
    }

    @Test
    void slipOptionsReachTheRobotsLoop() {
        CommandRun r = run("--scenario", "goal", "--slip-noise", "0", "--slip-bias", "0");
        assertEquals(0, r.status(), r.err());
        assertTrue(r.lastLine().contains("\"slip_noise\":0.00000,\"slip_bias\":0.00000,\"mission\":\"done\""),
                r.lastLine());
    }

    @Test
    void algorithmStudyOptionsAreRefusedForTheRobotsLoop() {
        CommandRun r = run("--scenario", "goal", "--controller", "pseudoinverse", "--calibrated");
        assertEquals(2, r.status());
        assertEquals("sabot simulate: error: --controller, --calibrated: not for --scenario goal (the robot's loop "
                + "runs the tracker task's DFL and its EKF)", r.err().strip());
        assertEquals("", r.out());
    }

    @Test
    void anUnknownScenarioIsRefusedByName() {
        CommandRun r = run("--scenario", "spiral");
        assertEquals(2, r.status());
        assertEquals("sabot simulate: error: unknown scenario 'spiral' (expected lemniscate|circle|square|offset|"
                + "stabilize) or goal (the robot's loop)", r.err().strip());
    }
}
