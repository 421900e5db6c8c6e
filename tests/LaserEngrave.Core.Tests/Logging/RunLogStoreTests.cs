using LaserEngrave.Core.Logging;

namespace LaserEngrave.Core.Tests.Logging;

public sealed class RunLogStoreTests : IDisposable
{
    private readonly TestRuns runs = new();

    private string LogFolder => Path.Combine(runs.Folder, "logs");

    [Fact]
    public void Write_NewFolder_WritesJsonAndTextNamedByStartTimeAndSample()
    {
        var store = new RunLogStore(LogFolder);

        var files = store.Write(runs.FailedRecord());

        Assert.Equal(Path.Combine(LogFolder, "2026-11-23_143005_S-17.json"), files.JsonPath);
        Assert.Equal(Path.Combine(LogFolder, "2026-11-23_143005_S-17.txt"), files.TextPath);
        Assert.Equal(runs.FailedRecord().Image, RunLogStore.Read(files.JsonPath).Image);
        Assert.Contains("S-17", File.ReadAllText(files.TextPath), StringComparison.Ordinal);
    }

    [Fact]
    public void Write_SameNameThreeTimes_AddsSuffixesAndNeverOverwrites()
    {
        var store = new RunLogStore(LogFolder);
        var first = store.Write(runs.FailedRecord() with { Notes = "one" });

        var second = store.Write(runs.FailedRecord() with { Notes = "two" });
        var third = store.Write(runs.FailedRecord() with { Notes = "three" });

        Assert.EndsWith("_S-17-2.json", second.JsonPath, StringComparison.Ordinal);
        Assert.EndsWith("_S-17-3.txt", third.TextPath, StringComparison.Ordinal);
        Assert.Equal("one", RunLogStore.Read(first.JsonPath).Notes);
        Assert.Equal("two", RunLogStore.Read(second.JsonPath).Notes);
        Assert.Equal("three", RunLogStore.Read(third.JsonPath).Notes);
    }

    [Fact]
    public void Write_OnlyTheTextNameTaken_SkipsThePairAndLeavesTheFileAlone()
    {
        Directory.CreateDirectory(LogFolder);
        var taken = Path.Combine(LogFolder, "2026-11-23_143005_S-17.txt");
        File.WriteAllText(taken, "someone's notes");

        var files = new RunLogStore(LogFolder).Write(runs.FailedRecord());

        Assert.EndsWith("_S-17-2.json", files.JsonPath, StringComparison.Ordinal);
        Assert.Equal("someone's notes", File.ReadAllText(taken));
        Assert.False(File.Exists(Path.ChangeExtension(taken, ".json")));
    }

    [Theory]
    [InlineData(null, "2026-11-23_143005")]
    [InlineData("  ", "2026-11-23_143005")]
    [InlineData("../etc/passwd", "2026-11-23_143005_etc_passwd")]
    [InlineData("..", "2026-11-23_143005")]
    [InlineData("Probe 3: Si/SiO2", "2026-11-23_143005_Probe_3_Si_SiO2")]
    [InlineData("Muestra ñ-01 ±5 µm", "2026-11-23_143005_Muestra_ñ-01_5_µm")]
    [InlineData("試料 7", "2026-11-23_143005_試料_7")]
    [InlineData("a\\b<c>d|e?f*g\"h", "2026-11-23_143005_a_b_c_d_e_f_g_h")]
    public void FileStem_SampleId_MadeSafeForAFileName(string? sample, string expected)
    {
        Assert.Equal(expected, RunLogStore.FileStem(runs.FailedRecord(sample)));
    }

    [Fact]
    public void List_SeveralRunsAndABadFile_NewestFirstThenTheBadOneWithItsError()
    {
        var store = new RunLogStore(LogFolder);
        var older = store.Write(runs.FailedRecord("old") with { StartedAt = TestRuns.Start.AddDays(-1) });
        var newer = store.Write(runs.FailedRecord("new"));
        File.WriteAllText(Path.Combine(LogFolder, "broken.json"), "{ not json");

        var entries = store.List();

        Assert.Equal([newer.JsonPath, older.JsonPath, Path.Combine(LogFolder, "broken.json")], entries.Select(e => e.Path));
        Assert.Equal("new", entries[0].Record?.SampleId);
        Assert.Null(entries[2].Record);
        Assert.StartsWith(Path.Combine(LogFolder, "broken.json") + ": not a run log", entries[2].Error, StringComparison.Ordinal);
    }

    [Fact]
    public void Write_FolderUnderAFile_ThrowsOneLineNamingTheFolder()
    {
        var file = Path.Combine(runs.Folder, "a-file");
        File.WriteAllText(file, "x");
        var store = new RunLogStore(Path.Combine(file, "logs"));

        var ex = Assert.Throws<RunLogException>(() => store.Write(runs.FailedRecord()));

        Assert.StartsWith($"{store.Folder}: cannot create the log folder", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void CheckWritable_FolderUnderAFile_OneLineNamingTheFolder()
    {
        var file = Path.Combine(runs.Folder, "a-file");
        File.WriteAllText(file, "x");
        var store = new RunLogStore(Path.Combine(file, "logs"));

        var ex = Assert.Throws<RunLogException>(store.CheckWritable);

        Assert.StartsWith($"{store.Folder}: cannot create the log folder", ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
    }

    [Theory]
    [InlineData(true)]
    [InlineData(false)]
    public void CheckWritable_ReadOnlyOrFullDisk_OneLineAndNothingLeftInTheFolder(bool full)
    {
        var store = new RunLogStore(LogFolder, full ? new FullDisk() : new ReadOnlyDisk());

        var ex = Assert.Throws<RunLogException>(store.CheckWritable);

        Assert.StartsWith($"{store.Folder}: cannot write the run log there: ", ex.Message, StringComparison.Ordinal);
        Assert.Contains(full ? "No space left on device" : "Read-only file system", ex.Message, StringComparison.Ordinal);
        Assert.Empty(Directory.GetFiles(LogFolder));
    }

    [Fact]
    public void CheckWritable_DiskWithLessRoomThanALog_SaysItIsFull()
    {
        var store = new RunLogStore(LogFolder, new AlmostFullDisk());

        var ex = Assert.Throws<RunLogException>(store.CheckWritable);

        Assert.Contains("the log folder's disk is full (10 kB free", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void CheckWritable_WritableFolder_LeavesNothingBehind()
    {
        var store = new RunLogStore(LogFolder);

        store.CheckWritable();

        Assert.Empty(Directory.GetFiles(LogFolder));
    }

    [Fact]
    public void Write_DiskFillsWhileWriting_NoLogNoEmptySummaryNoPartialFile()
    {
        var store = new RunLogStore(LogFolder, new FullDisk { FreeBytes = 3000 });

        var ex = Assert.Throws<RunLogException>(() => store.Write(runs.FailedRecord()));

        Assert.Contains("No space left on device", ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
        Assert.Empty(Directory.GetFiles(LogFolder));
        Assert.Empty(store.List());
    }

    /// <summary>A disk that takes <see cref="FreeBytes"/> and then fails every write as a full one does.</summary>
    private sealed class FullDisk : RunLogFileSystem
    {
        public long FreeBytes { get; init; }

        public override Stream CreateNew(string path) => new Filling(base.CreateNew(path), this);

        public override long? AvailableBytes(string folder) => FreeBytes;

        private sealed class Filling(Stream inner, FullDisk disk) : Stream
        {
            public override bool CanRead => false;

            public override bool CanSeek => false;

            public override bool CanWrite => true;

            public override long Length => inner.Length;

            public override long Position { get => inner.Position; set => throw new NotSupportedException(); }

            public override void Write(byte[] buffer, int offset, int count)
            {
                var room = (int)Math.Max(0, Math.Min(count, disk.FreeBytes - inner.Length));
                inner.Write(buffer, offset, room);
                if (room < count)
                {
                    throw new IOException("No space left on device");
                }
            }

            public override void Flush() => inner.Flush();

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

    /// <summary>A read-only mount (which a test run as root cannot get from chmod).</summary>
    private sealed class ReadOnlyDisk : RunLogFileSystem
    {
        public override Stream CreateNew(string path) => throw new IOException("Read-only file system");
    }

    /// <summary>A disk that takes the check's file but has only 10 kB left for anything after it.</summary>
    private sealed class AlmostFullDisk : RunLogFileSystem
    {
        public override long? AvailableBytes(string folder) => 10 * 1024;
    }

    [Fact]
    public void List_FolderMissing_IsEmpty()
    {
        Assert.Empty(new RunLogStore(Path.Combine(runs.Folder, "nothing-here")).List());
    }

    [Fact]
    public void Read_MissingFile_OneLineSayingSo()
    {
        var path = Path.Combine(runs.Folder, "gone.json");

        var ex = Assert.Throws<RunLogException>(() => RunLogStore.Read(path));

        Assert.Equal($"{path}: no such run log", ex.Message);
    }

    [Fact]
    public void Read_TextSummaryPath_ReadsTheJsonBesideIt()
    {
        var files = new RunLogStore(LogFolder).Write(runs.FailedRecord());

        Assert.Equal("S-17", RunLogStore.Read(files.TextPath).SampleId);
    }

    [Fact]
    public void DefaultFolderFrom_DocumentsKnown_IsLaserEngraveUnderDocuments()
    {
        var folder = RunLogStore.DefaultFolderFrom(f => f == Environment.SpecialFolder.MyDocuments ? "/home/ana/Documents" : "/home/ana", "/work");

        Assert.Equal(Path.Combine("/home/ana/Documents", "LaserEngrave"), folder);
    }

    [Fact]
    public void DefaultFolderFrom_NoDocumentsFolder_FallsBackToDocumentsUnderHome()
    {
        var folder = RunLogStore.DefaultFolderFrom(f => f == Environment.SpecialFolder.UserProfile ? "/home/ana" : string.Empty, "/work");

        Assert.Equal(Path.Combine("/home/ana", "Documents", "LaserEngrave"), folder);
    }

    [Fact]
    public void DefaultFolderFrom_NoHomeEither_FallsBackToTheCurrentDirectory()
    {
        Assert.Equal(Path.Combine("/work", "LaserEngrave"), RunLogStore.DefaultFolderFrom(_ => string.Empty, "/work"));
    }

    public void Dispose() => runs.Dispose();
}
