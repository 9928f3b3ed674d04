package sabot.tools.plan;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import sabot.tools.CommandRun;

/** {@code sabot plan}: the JSON last line, and one clear error line with a non-zero exit for bad input. */
class PlanCommandTest {

    @TempDir
    Path folder;

    private static CommandRun run(String... args) {
        return CommandRun.of(PlanCommand::run, args);
    }

    /** 20 x 10 costmap image, a wall at column 10 from the image's top down to row 7 (a gap at the bottom). */
    private Path costmapFile() throws IOException {
        int width = 20;
        int height = 10;
        byte[] header = ("P5\n" + width + " " + height + "\n255\n").getBytes(StandardCharsets.US_ASCII);
        byte[] bytes = java.util.Arrays.copyOf(header, header.length + width * height);
        for (int row = 0; row <= 7; row++) {
            bytes[header.length + row * width + 10] = (byte) 254;
        }
        Path file = folder.resolve("costs.pgm");
        Files.write(file, bytes);
        return file;
    }

    @Test
    void plansOnACostmapImageWithCellCoordinatesAndPrintsJson() throws IOException {
        Path png = folder.resolve("out.png");
        CommandRun r = run("--costmap", costmapFile().toString(), "--start", "2,2", "--goal", "17,2", "--cells", "--repeat", "3",
                "--png", png.toString());
        assertEquals(0, r.status(), r.err());
        String json = r.lastLine();
        assertTrue(json.startsWith("{") && json.endsWith("}"), json);
        assertTrue(json.contains("\"status\":\"ok\"") && json.contains("\"cells\":200") && json.contains("\"repeat\":3"),
                json);
        for (String key : new String[] { "median_ms", "min_ms", "path_length", "path_cost", "waypoints", "reason" }) {
            assertTrue(json.contains("\"" + key + "\":"), key + " missing in " + json);
        }
        assertTrue(Files.size(png) > 100);
    }

    @Test
    void twoThreadsAreReportedAndGiveTheSamePath() throws IOException {
        String costs = costmapFile().toString();
        CommandRun one = run("--costmap", costs, "--start", "2,2", "--goal", "17,2", "--cells");
        CommandRun two = run("--costmap", costs, "--start", "2,2", "--goal", "17,2", "--cells", "--threads", "2");
        assertEquals(0, two.status(), two.err());
        assertTrue(two.lastLine().contains("\"threads\":2") && one.lastLine().contains("\"threads\":1"), two.lastLine());
        // both compute on the calling thread: the same computation, so the same path
        String path = "\"path_length\"";
        assertEquals(one.lastLine().substring(one.lastLine().indexOf(path)), two.lastLine().substring(two.lastLine()
                .indexOf(path)));
    }

    @Test
    void referencePlannerAndUnreachableGoalAreReportedInJson() throws IOException {
        CommandRun r = run("--costmap", costmapFile().toString(), "--start", "2,2", "--goal", "10,2", "--cells", "--planner",
                "reference");
        assertEquals(0, r.status(), r.err());
        assertTrue(r.lastLine().contains("\"status\":\"unreachable\"") && r.lastLine().contains("\"goal_in_obstacle\""),
                r.lastLine());
        assertTrue(r.lastLine().contains("\"planner\":\"reference\""));
    }

    @ParameterizedTest
    @CsvSource(delimiter = '|', value = {
            "--start 1,1 --goal 2,2|give exactly one of --map",
            "--costmap COSTS --goal 2,2|missing --start",
            "--costmap COSTS --start 1,1|missing --goal",
            "--costmap COSTS --start 1 --goal 2,2|is not X,Y",
            "--costmap COSTS --start NaN,1 --goal 2,2|not a finite number",
            "--costmap COSTS --start 1,1 --goal 2,2 --cells --repeat 0|positive integer",
            "--costmap COSTS --start 1,1 --goal 99,2 --cells|outside the 20 x 10 map",
            "--costmap COSTS --start 1,1 --goal 2,2 --planner magic|unknown planner 'magic'",
            "--costmap COSTS --start 1,1 --goal 2,2 --threads 3|--threads must be 1 or 2, not 3",
            "--costmap COSTS --start 1,1 --goal 2,2 --threads 0|positive integer",
            "--costmap COSTS --start 1,1 --goal 2,2 --resolution -1|must be positive",
            "--costmap COSTS --start 1,1 --goal 2,2 --frobnicate|unknown argument",
            "--costmap MISSING --start 1,1 --goal 2,2|image file does not exist",
            "--map MISSING --start 1,1 --goal 2,2|map file does not exist" })
    void badInputIsOneClearErrorLineAndNonZeroExit(String args, String expected) throws IOException {
        String costs = costmapFile().toString();
        String[] parts = args.replace("COSTS", costs).replace("MISSING", folder.resolve("nothere").toString()).split(" ");
        CommandRun r = run(parts);
        assertEquals(2, r.status());
        assertEquals("", r.out());
        assertEquals(1, r.err().strip().lines().count(), r.err());
        assertTrue(r.err().startsWith("sabot plan: error: ") && r.err().contains(expected), r.err());
    }
}
