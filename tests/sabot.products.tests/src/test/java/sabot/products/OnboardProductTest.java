package sabot.products;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** The materialized onboard product, started as a real process. */
class OnboardProductTest {

    private static final Path PRODUCT = ProductProcess.product("sabot.onboard.product", "sabot-onboard");

    @TempDir
    Path dir;

    private ProductProcess start(String config) throws Exception {
        Path file = dir.resolve("onboard.conf");
        Files.writeString(file, config);
        return ProductProcess.start(PRODUCT, List.of(), List.of("-config", file.toString()));
    }

    @Test
    void startsLogsVersionAndTasksAndStopsCleanlyOnSigterm() throws Exception {
        try (ProductProcess p = start("robot.name = r2\ntasks = heartbeat\nheartbeat.period = 1\n")) {
            String started = p.await(l -> l.contains("task(s) loaded"), "listing the loaded tasks");
            assertTrue(started.matches(".*Sabot Onboard \\d+\\.\\d+\\.\\d+\\.\\S+ running as 'r2': 1 task\\(s\\) "
                    + "loaded: heartbeat$"), started);
            p.await(l -> l.contains("heartbeat #1: uptime"), "with the first heartbeat");

            p.terminate();

            assertEquals(0, p.waitFor(), p.output());
            List<String> lines = p.lines();
            assertTrue(lines.stream().anyMatch(l -> l.contains("received SIGTERM")), p.output());
            assertTrue(lines.stream().anyMatch(l -> l.contains("heartbeat task stopped")), p.output());
            assertTrue(lines.get(lines.size() - 1).endsWith("Sabot Onboard stopped"), "not the last line: "
                    + p.output());
        }
    }

    @Test
    void heartbeatSwitchedOffInTheFileDoesNotRun() throws Exception {
        try (ProductProcess p = start("tasks =\nheartbeat.period = 1\n")) {
            p.await(l -> l.contains("0 task(s) loaded: none"), "saying no task is loaded");
            p.terminate();
            assertEquals(0, p.waitFor(), p.output());
            assertFalse(p.output().contains("heartbeat task started"), p.output());
        }
    }

    @Test
    void brokenConfigurationGivesOneErrorLineNamingFileAndKeyAndExitsNonZero() throws Exception {
        try (ProductProcess p = start("tasks = heartbeat\n\nheartbeat.period = fast\n")) {
            int status = p.waitFor();
            assertEquals(2, status, p.output());
            List<String> errors = p.lines().stream().filter(l -> l.contains("ERROR")).toList();
            assertEquals(1, errors.size(), p.output());
            assertTrue(errors.get(0).endsWith(dir.resolve("onboard.conf") + ":3: key 'heartbeat.period': 'fast' is "
                    + "not an integer"), errors.get(0));
            assertFalse(p.output().contains("heartbeat task started"), p.output());
        }
    }

    @Test
    void unknownTaskIsRefusedNamingTheAvailableOnes() throws Exception {
        try (ProductProcess p = start("tasks = heartbeat, teleport\n")) {
            assertEquals(2, p.waitFor(), p.output());
            assertTrue(p.output().contains(":1: key 'tasks': unknown task 'teleport' (available: bus, controlml, "
                    + "heartbeat, localizer, motion, peers, planner, portal, remotefs, teleop, tracker)"),
                    p.output());
        }
    }

    @Test
    void missingConfigurationFileIsReported() throws Exception {
        try (ProductProcess p = ProductProcess.start(PRODUCT, List.of(), List.of("-config", dir.resolve("absent.conf")
                .toString()))) {
            assertEquals(2, p.waitFor(), p.output());
            assertTrue(p.output().contains(dir.resolve("absent.conf") + ": file not found"), p.output());
        }
    }
}
