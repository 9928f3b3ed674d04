package sabot.controlml.bench;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class WorkbenchBenchTest {

    @Test
    void theGcPausesThatBeganInTheWindowAreReadFromTheLogOfEitherCollector(@TempDir Path dir) throws IOException {
        Path log = dir.resolve(WorkbenchBench.GC_LOG);
        // the stamp is the end of the line's event: a pause began at the stamp minus its duration
        Files.writeString(log, String.join("\n",
                "[1000000ms] Using Serial",
                "[1000500ms] GC(0) Pause Young (Allocation Failure) 102M->11M(365M) 23.513ms", // began 1000476: before
                "[1001030ms] GC(1) Pause Young (Allocation Failure) 119M->21M(365M) 12.621ms", // began 1001017
                "[1001500ms] GC(2) Pause Young (Normal) (G1 Evacuation Pause) 25M->5M(64M) 3.456ms",
                "[1001600ms] GC(3) Concurrent Mark Cycle 12.000ms", // concurrent: not a pause
                "[1001700ms] GC(3) Pause Remark 40M->40M(64M) 1.250ms",
                // began at 1002000.1: after the window
                "[1002001ms] GC(4) Pause Young (Normal) (G1 Evacuation Pause) 25M->5M(64M) 0.900ms",
                ""));
        assertEquals(List.of(12_621_000L, 3_456_000L, 1_250_000L), WorkbenchBench.gcPauses(log, 1_001_000,
                1_002_000));
    }

    @Test
    void noLogMeansNoPauses(@TempDir Path dir) throws IOException {
        assertEquals(List.of(), WorkbenchBench.gcPauses(dir.resolve("missing.log"), 0, Long.MAX_VALUE));
    }

    @Test
    void theGrowthSlopeIsTheLeastSquaresLine() {
        assertEquals(0.5, WorkbenchBench.slope(List.of(new double[] { 0, 10 }, new double[] { 2, 11 }, new double[] {
                4, 12 }), 1), 1e-12);
    }
}
