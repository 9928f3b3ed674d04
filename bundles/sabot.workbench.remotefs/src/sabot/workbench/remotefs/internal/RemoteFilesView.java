package sabot.workbench.remotefs.internal;

import java.io.IOException;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

import org.eclipse.core.runtime.IStatus;
import org.eclipse.core.runtime.OperationCanceledException;
import org.eclipse.core.runtime.Status;
import org.eclipse.core.runtime.SubMonitor;
import org.eclipse.core.runtime.jobs.Job;
import org.eclipse.jface.dialogs.MessageDialog;
import org.eclipse.jface.viewers.ColumnLabelProvider;
import org.eclipse.jface.viewers.IStructuredSelection;
import org.eclipse.jface.viewers.ITreeContentProvider;
import org.eclipse.jface.viewers.TreeViewer;
import org.eclipse.jface.viewers.TreeViewerColumn;
import org.eclipse.swt.SWT;
import org.eclipse.swt.dnd.DND;
import org.eclipse.swt.dnd.DropTarget;
import org.eclipse.swt.dnd.DropTargetAdapter;
import org.eclipse.swt.dnd.DropTargetEvent;
import org.eclipse.swt.dnd.FileTransfer;
import org.eclipse.swt.dnd.Transfer;
import org.eclipse.swt.layout.GridData;
import org.eclipse.swt.layout.GridLayout;
import org.eclipse.swt.layout.RowLayout;
import org.eclipse.swt.widgets.Button;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.FileDialog;
import org.eclipse.swt.widgets.Tree;
import org.eclipse.swt.widgets.TreeItem;

import sabot.controlml.Role;
import sabot.controlml.payload.FileEntry;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.remotefs.internal.RemoteFiles.RemoteFsException;
import sabot.workbench.robotview.RobotView;

/**
 * The chosen robot's remote FS as a tree with name and size columns: directories open on demand (listed by a job),
 * files upload (button or drag and drop from the desktop onto a directory), download and delete, each as a job with
 * a progress monitor the operator can cancel (Progress view, or the job's own cancel). Every refusal shows the robot's
 * reason on the message line.
 */
public final class RemoteFilesView extends RobotView {

    public static final String ID = "sabot.workbench.remotefs.view";
    static final String LOADING = "(listing...)";

    /** A file or directory of the robot; the root is the directory with the empty path. */
    public record Node(String path, FileEntry entry) {
        boolean directory() {
            return entry == null || entry.directory();
        }

        String name() {
            return entry == null ? "/" : entry.name();
        }

        /** @return the directory an upload onto this node goes into */
        String directoryPath() {
            if (directory()) {
                return path;
            }
            int slash = path.lastIndexOf('/');
            return slash < 0 ? "" : path.substring(0, slash);
        }
    }

    private static final Node ROOT = new Node("", null);

    private TreeViewer viewer;
    /** Writes and deletes: the maintainer's (docs/CONTROLML.md section 9). */
    private Button uploadButton;
    private Button deleteButton;
    private final Map<String, List<Node>> listed = new ConcurrentHashMap<>();
    private final Map<String, Job> listing = new ConcurrentHashMap<>();
    private String shownRobot;

    @Override
    protected void createContent(Composite parent) {
        parent.setLayout(new GridLayout(1, false));
        Composite buttons = new Composite(parent, SWT.NONE);
        buttons.setLayout(new RowLayout());
        button(buttons, "Refresh", this::refresh);
        uploadButton = button(buttons, "Upload...", this::uploadChosen);
        button(buttons, "Download...", this::downloadSelected);
        deleteButton = button(buttons, "Delete", this::deleteSelected);

        viewer = new TreeViewer(parent, SWT.BORDER | SWT.FULL_SELECTION | SWT.MULTI);
        Tree tree = viewer.getTree();
        tree.setHeaderVisible(true);
        tree.setLayoutData(new GridData(SWT.FILL, SWT.FILL, true, true));
        column("Name", 260, n -> n.path().equals(LOADING) ? LOADING : n.name());
        column("Size", 100, n -> n.entry() == null || n.entry().directory() ? "" : n.entry().size() + " B");
        viewer.setContentProvider(new ITreeContentProvider() {
            @Override
            public Object[] getElements(Object input) {
                return getChildren(ROOT);
            }

            @Override
            public Object[] getChildren(Object parent) {
                Node dir = (Node) parent;
                List<Node> children = listed.get(dir.path());
                if (children == null) {
                    startListing(dir.path());
                    return new Object[] { new Node(LOADING, null) };
                }
                return children.toArray();
            }

            @Override
            public Object getParent(Object element) {
                return null;
            }

            @Override
            public boolean hasChildren(Object element) {
                Node n = (Node) element;
                return n.directory() && !n.path().equals(LOADING) && !(listed.containsKey(n.path()) && listed.get(
                        n.path()).isEmpty());
            }
        });
        DropTarget drop = new DropTarget(tree, DND.DROP_COPY | DND.DROP_DEFAULT);
        drop.setTransfer(new Transfer[] { FileTransfer.getInstance() });
        drop.addDropListener(new DropTargetAdapter() {
            @Override
            public void dragEnter(DropTargetEvent e) {
                e.detail = DND.DROP_COPY;
            }

            @Override
            public void drop(DropTargetEvent e) {
                if (e.data instanceof String[] files) {
                    Node target = e.item instanceof TreeItem item && item.getData() instanceof Node n ? n : ROOT;
                    upload(java.util.Arrays.stream(files).map(Paths::get).toList(), target.directoryPath());
                }
            }
        });
    }

    private Button button(Composite parent, String text, Runnable action) {
        Button b = new Button(parent, SWT.PUSH);
        b.setText(text);
        b.addListener(SWT.Selection, e -> action.run());
        return b;
    }

    private void column(String title, int width, java.util.function.Function<Node, String> text) {
        TreeViewerColumn c = new TreeViewerColumn(viewer, SWT.LEFT);
        c.getColumn().setText(title);
        c.getColumn().setWidth(width);
        c.setLabelProvider(new ColumnLabelProvider() {
            @Override
            public String getText(Object element) {
                return text.apply((Node) element);
            }
        });
    }

    @Override
    protected void robotChanged(RobotState state, boolean newRobot) {
        gate(uploadButton, Role.MAINTAINER, "Uploading files");
        gate(deleteButton, Role.MAINTAINER, "Deleting files");
        if (newRobot || shownRobot == null && state != null) {
            shownRobot = state == null ? null : state.jid();
            listed.clear();
            viewer.setInput(shownRobot == null ? null : ROOT);
        }
    }

    /** Lists the root again and forgets the directories listed before. */
    public void refresh() {
        listed.clear();
        viewer.setInput(robot() == null ? null : ROOT);
    }

    private void startListing(String dir) {
        String robot = robot();
        FleetState fleet = fleet();
        if (robot == null || fleet == null || listing.containsKey(dir)) {
            return;
        }
        Display display = viewer.getControl().getDisplay();
        Job job = Job.create(robot + ": list /" + dir, monitor -> {
            try {
                List<FileEntry> entries = new RemoteFiles(fleet, robot).list(dir, monitor);
                List<Node> nodes = new ArrayList<>();
                for (FileEntry e : entries) {
                    nodes.add(new Node(RemoteFiles.child(dir, e.name()), e));
                }
                display.asyncExec(() -> {
                    listing.remove(dir);
                    if (robot.equals(robot()) && !viewer.getControl().isDisposed()) {
                        listed.put(dir, nodes);
                        viewer.refresh();
                    }
                });
            } catch (RemoteFsException e) {
                listing.remove(dir);
                showMessageLater(robot + ": list /" + dir + ": " + e.getMessage(), true);
            }
            return Status.OK_STATUS;
        });
        listing.put(dir, job);
        job.schedule();
    }

    // ---------------------------------------------------------------------------------------- operator actions

    private void uploadChosen() {
        FileDialog dialog = new FileDialog(viewer.getControl().getShell(), SWT.OPEN | SWT.MULTI);
        dialog.setText("Upload to " + robot());
        if (dialog.open() == null) {
            return;
        }
        List<Path> files = java.util.Arrays.stream(dialog.getFileNames()).map(n -> Paths.get(dialog.getFilterPath(),
                n)).toList();
        upload(files, selectedDirectory());
    }

    private void downloadSelected() {
        Node n = selected();
        if (n == null || n.directory()) {
            showMessage("Download: select a file", true);
            return;
        }
        FileDialog dialog = new FileDialog(viewer.getControl().getShell(), SWT.SAVE);
        dialog.setFileName(n.name());
        dialog.setOverwrite(true);
        String local = dialog.open();
        if (local != null) {
            download(n.path(), Paths.get(local));
        }
    }

    private void deleteSelected() {
        Node n = selected();
        if (n == null || n == ROOT) {
            showMessage("Delete: select a file or an empty directory", true);
            return;
        }
        if (MessageDialog.openConfirm(viewer.getControl().getShell(), "Delete", "Delete " + n.path() + " on "
                + robot() + "?")) {
            delete(n.path());
        }
    }

    private Node selected() {
        return viewer.getStructuredSelection() instanceof IStructuredSelection s && s.getFirstElement() instanceof Node n
                && !n.path().equals(LOADING) ? n : null;
    }

    private String selectedDirectory() {
        Node n = selected();
        return n == null ? "" : n.directoryPath();
    }

    /**
     * Uploads local files into a directory of the robot, one job for all (cancelling it stops after the chunk in
     * flight; the robot discards the hidden partial file when a new transfer of that file starts).
     *
     * @return the scheduled job, or null without a chosen robot
     */
    public Job upload(List<Path> files, String remoteDir) {
        return transfer("upload " + files.size() + " file(s) to /" + remoteDir, (remote, monitor) -> {
            SubMonitor all = SubMonitor.convert(monitor, files.size());
            for (Path f : files) {
                remote.upload(f, RemoteFiles.child(remoteDir, f.getFileName().toString()), all.split(1));
            }
        }, remoteDir);
    }

    /** Downloads one file of the robot to a local path. */
    public Job download(String remotePath, Path local) {
        long size = listed.values().stream().flatMap(List::stream).filter(n -> n.path().equals(remotePath) && n
                .entry() != null).mapToLong(n -> n.entry().size()).findFirst().orElse(0);
        return transfer("download /" + remotePath, (remote, monitor) -> remote.download(remotePath, size, local,
                monitor), null);
    }

    /** Deletes a file or an empty directory of the robot. */
    public Job delete(String remotePath) {
        int slash = remotePath.lastIndexOf('/');
        return transfer("delete /" + remotePath, (remote, monitor) -> remote.delete(remotePath), slash < 0 ? ""
                : remotePath.substring(0, slash));
    }

    @FunctionalInterface
    private interface TransferBody {
        void run(RemoteFiles remote, org.eclipse.core.runtime.IProgressMonitor monitor) throws RemoteFsException,
                IOException;
    }

    /** Runs a user job (progress shown, cancellable); on success lists {@code changedDir} again. */
    private Job transfer(String what, TransferBody body, String changedDir) {
        String robot = robot();
        FleetState fleet = fleet();
        if (robot == null || fleet == null) {
            showMessage(what + ": " + (robot == null ? "choose a robot first" : "no fleet"), true);
            return null;
        }
        String label = robot + ": " + what;
        Display display = viewer.getControl().getDisplay();
        Job job = new Job(label) {
            @Override
            protected IStatus run(org.eclipse.core.runtime.IProgressMonitor monitor) {
                String failure;
                try {
                    body.run(new RemoteFiles(fleet, robot), monitor);
                    failure = null;
                } catch (RemoteFsException e) {
                    failure = e.getMessage();
                } catch (OperationCanceledException e) {
                    failure = "cancelled";
                } catch (IOException e) {
                    failure = "local file: " + e;
                }
                String f = failure;
                display.asyncExec(() -> {
                    showMessage(f == null ? label + ": done" : label + ": " + f, f != null);
                    if (f == null && changedDir != null && robot.equals(robot()) && !viewer.getControl()
                            .isDisposed()) {
                        listed.remove(changedDir);
                        viewer.refresh();
                    }
                });
                return f != null && f.equals("cancelled") ? Status.CANCEL_STATUS : Status.OK_STATUS;
            }
        };
        job.setUser(true);
        job.schedule();
        return job;
    }

    /** @return the entries of a directory as last listed, or null when it was not listed (yet) */
    public List<FileEntry> listed(String dir) {
        List<Node> nodes = listed.get(dir);
        return nodes == null ? null : nodes.stream().map(Node::entry).toList();
    }

    /** @return the tree (for tests and screenshots) */
    public TreeViewer viewer() {
        return viewer;
    }
}
