package sabot.workbench.internal;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.nio.file.StandardCopyOption;

import org.eclipse.ui.PlatformUI;

/**
 * The UI tests' screenshots: saved under {@code sabot.screenshots} (the test module's target) and copied to the
 * repository's {@code docs/images} (when {@code sabot.root} names it), where the documents show them.
 */
public final class DocScreenshots {

    private DocScreenshots() {
    }

    /** Saves the workbench window as the display shows it, as {@code name} (a PNG), and copies it to the docs. */
    public static Path window(String name) throws Exception {
        Path png = screenshots().resolve(name);
        SabotWindowAdvisor.saveScreenshot(PlatformUI.getWorkbench().getActiveWorkbenchWindow().getShell(), png);
        toDocs(png);
        return png;
    }

    /** @return the folder of the test run's screenshots, made when missing */
    public static Path screenshots() throws Exception {
        return Files.createDirectories(Paths.get(System.getProperty("sabot.screenshots", "target/screenshots")));
    }

    /** Copies a screenshot to the repository's {@code docs/images} (nothing when the tests run outside it). */
    public static void toDocs(Path png) throws Exception {
        String root = System.getProperty("sabot.root");
        if (root != null && Files.isDirectory(Paths.get(root, "docs"))) {
            Path docs = Files.createDirectories(Paths.get(root, "docs", "images"));
            Files.copy(png, docs.resolve(png.getFileName()), StandardCopyOption.REPLACE_EXISTING);
        }
    }
}
