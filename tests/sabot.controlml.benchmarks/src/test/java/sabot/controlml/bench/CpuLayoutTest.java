package sabot.controlml.bench;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import org.junit.jupiter.api.Test;

class CpuLayoutTest {

    @Test
    void readsSingleCpusAndRangesOfTasksetsAnswer() {
        assertEquals(List.of(0, 1), CpuLayout.parseCpuList("pid 42's current affinity list: 0,1\n"));
        assertEquals(List.of(0, 2, 3, 4, 7), CpuLayout.parseCpuList("pid 7's current affinity list: 0,2-4,7"));
        assertEquals(List.of(3), CpuLayout.parseCpuList("pid 7's current affinity list: 3"));
    }

    @Test
    void anAnswerWithoutListIsRefused() {
        assertThrows(IllegalArgumentException.class, () -> CpuLayout.parseCpuList("taskset: failed"));
        assertThrows(IllegalArgumentException.class, () -> CpuLayout.parseCpuList("pid 7's current affinity list: x"));
    }

    @Test
    void aServerThatIsGoneLeavesTheCpusSharedAndSaysWhy() {
        assertLeftShared((1L << 22) + 1); // above any kernel's pid_max
    }

    @Test
    void aServerThatEndedLeavesTheCpusShared() throws Exception {
        Process ended = new ProcessBuilder("true").start();
        ended.waitFor();
        assertLeftShared(ended.pid());
    }

    private static void assertLeftShared(long serverPid) {
        long self = ProcessHandle.current().pid();
        List<Integer> before = CpuLayout.parseCpuList(answerFor(self));
        CpuLayout layout = CpuLayout.split(serverPid);
        assertTrue(layout.description().startsWith("shared ("), layout.description());
        assertEquals(before, CpuLayout.parseCpuList(answerFor(self)), "this JVM was moved");
    }

    @Test
    void theServerGetsTheLastCpuAndThisJvmTheOthers() throws Exception {
        long self = ProcessHandle.current().pid();
        List<Integer> before = CpuLayout.parseCpuList(answerFor(self));
        Process server = new ProcessBuilder("sleep", "60").start();
        try {
            CpuLayout layout = CpuLayout.split(server.pid());
            if (before.size() < 2) {
                assertEquals("shared (1 CPU)", layout.description());
                return;
            }
            int last = before.get(before.size() - 1);
            assertEquals(List.of(last), CpuLayout.parseCpuList(answerFor(server.pid())));
            assertEquals(before.subList(0, before.size() - 1), CpuLayout.parseCpuList(answerFor(self)));
            assertTrue(layout.description().startsWith("server cpu " + last + ", clients cpu "), layout.description());
        } finally {
            server.destroy();
            StringBuilder all = new StringBuilder();
            before.forEach(c -> all.append(all.length() == 0 ? "" : ",").append(c));
            new ProcessBuilder("taskset", "-a", "-p", "-c", all.toString(), Long.toString(self)).start().waitFor();
        }
    }

    @Test
    void workbenchAloneGivesTheServerAndTheLoadTheLastCpuAndTheStartedProcessesAndXTheOthers() throws Exception {
        long self = ProcessHandle.current().pid();
        List<Integer> before = CpuLayout.parseCpuList(answerFor(self));
        Process server = new ProcessBuilder("sleep", "60").start();
        Process x = new ProcessBuilder("sleep", "60").start();
        try {
            CpuLayout layout = CpuLayout.workbenchAlone(server.pid(), x.pid());
            if (before.size() < 2) {
                assertEquals("shared (1 CPU)", layout.description());
                return;
            }
            List<Integer> last = List.of(before.get(before.size() - 1));
            List<Integer> others = before.subList(0, before.size() - 1);
            assertEquals(last, CpuLayout.parseCpuList(answerFor(server.pid())));
            assertEquals(last, CpuLayout.parseCpuList(answerFor(self)));
            assertEquals(others, CpuLayout.parseCpuList(answerFor(x.pid())));
            List<String> wrapped = layout.wrap(List.of("java", "-version"));
            assertEquals(List.of("taskset", "-c"), wrapped.subList(0, 2));
            assertEquals(others, CpuLayout.parseCpuList(":" + wrapped.get(2)));
            assertEquals(List.of("java", "-version"), wrapped.subList(3, 5));
            assertTrue(layout.description().contains("workbench cpu "), layout.description());
        } finally {
            server.destroy();
            x.destroy();
            StringBuilder all = new StringBuilder();
            before.forEach(c -> all.append(all.length() == 0 ? "" : ",").append(c));
            new ProcessBuilder("taskset", "-a", "-p", "-c", all.toString(), Long.toString(self)).start().waitFor();
        }
    }

    private static String answerFor(long pid) {
        try {
            Process p = new ProcessBuilder("taskset", "-pc", Long.toString(pid)).redirectErrorStream(true).start();
            String out = new String(p.getInputStream().readAllBytes(), java.nio.charset.StandardCharsets.UTF_8);
            p.waitFor();
            return out;
        } catch (java.io.IOException | InterruptedException e) {
            throw new AssertionError(e);
        }
    }
}
