using LaserEngrave.Core.Logging;

namespace LaserEngrave.Core.Tests.Logging;

/// <summary>Issue 31 finding 6: a log folder that fails during a run must not lose the record that resumes it.</summary>
public sealed class FallbackRunLogWriterTests : IDisposable
{
    private readonly TestRuns runs = new();

    private string LogFolder => Path.Combine(runs.Folder, "logs");

    private string DataFolder => Path.Combine(runs.Folder, "data");

    private string TempFolder => Path.Combine(runs.Folder, "temp");

    [Fact]
    public void Write_LogFolderWorks_WritesThereWithoutNotice()
    {
        var writer = Writer(RunLogFileSystem.Real);

        var files = writer.Write(runs.FailedRecord());

        Assert.Equal(LogFolder, Path.GetDirectoryName(files.JsonPath));
        Assert.Null(files.Notice);
        Assert.False(Directory.Exists(DataFolder));
    }

    [Fact]
    public void Write_LogFolderReadOnly_WritesToTheDataFolderAndSaysWhereInOneLine()
    {
        // As root a chmod does not stop writes: the seam acts the read-only mount.
        var writer = Writer(new FaultyDisk(full: false, LogFolder));

        var files = writer.Write(runs.FailedRecord());

        Assert.Equal(DataFolder, Path.GetDirectoryName(files.JsonPath));
        Assert.Equal(runs.FailedRecord().StoppedAt, RunLogStore.Read(files.JsonPath).StoppedAt);
        Assert.Contains("S-17", File.ReadAllText(files.TextPath), StringComparison.Ordinal);
        Assert.Equal(
            $"the run log is in {files.JsonPath} instead: {Path.Combine(LogFolder, "2026-11-23_143005_S-17.json")}: cannot write the run log: Read-only file system",
            files.Notice);
    }

    [Fact]
    public void Write_LogFolderBecameAFileDuringTheRun_WritesToTheDataFolder()
    {
        var writer = Writer(RunLogFileSystem.Real);
        new RunLogStore(LogFolder).CheckWritable();
        // During the run, something puts a file where the folder was (a real failure, even for root).
        Directory.Delete(LogFolder, recursive: true);
        File.WriteAllText(LogFolder, "not a folder");

        var files = writer.Write(runs.FailedRecord());

        Assert.Equal(DataFolder, Path.GetDirectoryName(files.JsonPath));
        Assert.StartsWith($"the run log is in {files.JsonPath} instead: {LogFolder}: cannot create the log folder: ", files.Notice, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', files.Notice!);
    }

    [Fact]
    public void Write_LogAndDataFoldersOnAFullDisk_WritesToTheTemporaryFolderAndLeavesNoPartialFile()
    {
        var writer = Writer(new FaultyDisk(full: true, LogFolder, DataFolder));

        var files = writer.Write(runs.FailedRecord());

        Assert.Equal(TempFolder, Path.GetDirectoryName(files.JsonPath));
        Assert.Contains("No space left on device", files.Notice, StringComparison.Ordinal);
        Assert.Empty(Directory.GetFiles(LogFolder));
        Assert.Empty(Directory.GetFiles(DataFolder));
    }

    [Fact]
    public void Write_EveryFolderFails_OneLineNamingEachFolder()
    {
        var writer = Writer(new FaultyDisk(full: false, LogFolder, DataFolder, TempFolder));

        var ex = Assert.Throws<RunLogException>(() => writer.Write(runs.FailedRecord()));

        Assert.DoesNotContain('\n', ex.Message);
        Assert.StartsWith($"{Path.Combine(LogFolder, "2026-11-23_143005_S-17.json")}: cannot write the run log: Read-only file system; nor in a fallback folder: {Path.Combine(DataFolder, "2026-11-23_143005_S-17.json")}", ex.Message, StringComparison.Ordinal);
        Assert.Contains(TempFolder, ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void For_Store_FallsBackToTheDataFolderThenTheTemporaryFolderNeverTheFolderThatFailed()
    {
        Assert.Equal([DataFolder, Path.Combine(Path.GetTempPath(), "LaserEngrave")], FallbackRunLogWriter.FallbackFolders(DataFolder));

        // The data folder is the log folder: it is not tried twice, and the log goes to the next one.
        var disk = new FaultyDisk(full: false, LogFolder);
        var writer = new FallbackRunLogWriter(new RunLogStore(LogFolder, disk), LogFolder, [new RunLogStore(LogFolder, disk), new RunLogStore(TempFolder, disk)]);

        Assert.Equal(TempFolder, Path.GetDirectoryName(writer.Write(runs.FailedRecord()).JsonPath));
    }

    public void Dispose() => runs.Dispose();

    private FallbackRunLogWriter Writer(RunLogFileSystem disk) =>
        new(new RunLogStore(LogFolder, disk), LogFolder, [new RunLogStore(DataFolder, disk), new RunLogStore(TempFolder, disk)]);

    /// <summary>Folders on a read-only mount (every new file refused) or a full disk (every write fails after the file is made).</summary>
    private sealed class FaultyDisk(bool full, params string[] folders) : RunLogFileSystem
    {

        public override Stream CreateNew(string path)
        {
            if (!folders.Contains(Path.GetDirectoryName(path)))
            {
                return base.CreateNew(path);
            }

            return full ? new FullStream(base.CreateNew(path)) : throw new IOException("Read-only file system");
        }

        private sealed class FullStream(Stream inner) : Stream
        {
            public override bool CanRead => false;

            public override bool CanSeek => false;

            public override bool CanWrite => true;

            public override long Length => 0;

            public override long Position { get => 0; set => throw new NotSupportedException(); }

            public override void Write(byte[] buffer, int offset, int count) => throw new IOException("No space left on device");

            public override void Flush()
            {
            }

            public override int Read(byte[] buffer, int offset, int count) => throw new NotSupportedException();

            public override long Seek(long offset, SeekOrigin origin) => throw new NotSupportedException();

            public override void SetLength(long value) => throw new NotSupportedException();

            protected override void Dispose(bool disposing)
            {
                if (disposing)
                {
                    inner.Dispose();
                }

                base.Dispose(disposing);
            }
        }
    }
}
