package sabot.tools;

import java.io.ByteArrayOutputStream;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;

/**
 * One run of a command's {@code run(args, out, err)} in the test's JVM: its exit status and what it printed.
 *
 * @param status the exit status the command returned
 * @param out    what it printed on standard output
 * @param err    what it printed on standard error
 */
public record CommandRun(int status, String out, String err) {

    /** A command's entry point without {@code System.exit}: {@code PlanCommand::run}, {@code SimulateCommand::run}. */
    @FunctionalInterface
    public interface Command {
        int run(String[] args, PrintStream out, PrintStream err);
    }

    /** @return the run of {@code command} with {@code args} */
    public static CommandRun of(Command command, String... args) {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        ByteArrayOutputStream err = new ByteArrayOutputStream();
        int status = command.run(args, new PrintStream(out, true, StandardCharsets.UTF_8),
                new PrintStream(err, true, StandardCharsets.UTF_8));
        return new CommandRun(status, out.toString(StandardCharsets.UTF_8), err.toString(StandardCharsets.UTF_8));
    }

    /** @return the last line printed on standard output (the commands print their figures there as JSON) */
    public String lastLine() {
        String[] lines = out.strip().split("\n");
        return lines[lines.length - 1];
    }
}
