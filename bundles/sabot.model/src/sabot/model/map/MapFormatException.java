package sabot.model.map;

import java.io.IOException;
import java.nio.file.Path;

/** A map or image file that cannot be read as the ROS {@code map_server} format; the message names file and problem. */
public final class MapFormatException extends IOException {

    private static final long serialVersionUID = 1L;

    /** @param file the file at fault; {@code problem} says what is wrong with it */
    public MapFormatException(Path file, String problem) {
        super(file + ": " + problem);
    }

    /** @param file the file at fault; {@code line} (from 1) is where; {@code problem} says what is wrong there */
    public MapFormatException(Path file, int line, String problem) {
        super(file + ":" + line + ": " + problem);
    }
}
