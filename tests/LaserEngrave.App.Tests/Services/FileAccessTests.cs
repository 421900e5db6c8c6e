using LaserEngrave.App.Services;

namespace LaserEngrave.App.Tests.Services;

public sealed class FileAccessTests : IDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    private string Images => Path.Combine(_folder.Path, "images");

    public void Dispose() => _folder.Dispose();

    [Theory]
    [InlineData(null, null, false)]
    [InlineData(":0", null, true)]
    [InlineData(null, "wayland-0", true)]
    [InlineData("", "", false)]
    public void HasDesktop_Linux_OnlyInAnX11OrWaylandSession(string? display, string? wayland, bool onLinux)
    {
        var has = App.Services.FileAccess.HasDesktop(name => name == "DISPLAY" ? display : name == "WAYLAND_DISPLAY" ? wayland : null);

        // Windows and macOS always have a desktop to show the folder on.
        Assert.Equal(onLinux || OperatingSystem.IsWindows() || OperatingSystem.IsMacOS(), has);
    }

    [Fact]
    public async Task SaveUpload_OverTheLimit_RefusedNamingTheFileAndNothingLeft()
    {
        var files = new App.Services.FileAccess(new AppFolders(_folder.Path), maxUploadBytes: 1000);
        using var content = new MemoryStream(new byte[1001]);

        var error = await Assert.ThrowsAsync<UploadException>(() => files.SaveUploadAsync("holiday.png", content, Token));

        Assert.Equal("holiday.png: the file is larger than 1000 bytes, the most the app takes", error.Message);
        Assert.Empty(Directory.GetFiles(Images));
    }

    [Fact]
    public async Task SaveUpload_StreamBreaks_RefusedNamingTheFileAndNothingLeft()
    {
        var files = new App.Services.FileAccess(new AppFolders(_folder.Path));
        using var content = new BreakingStream();

        var error = await Assert.ThrowsAsync<UploadException>(() => files.SaveUploadAsync("scan.bmp", content, Token));

        Assert.StartsWith("scan.bmp: ", error.Message, StringComparison.Ordinal);
        Assert.Empty(Directory.GetFiles(Images));
    }

    [Fact]
    public async Task SaveUpload_AtTheLimit_KeptUnderItsNameInItsContentsFolder()
    {
        var files = new App.Services.FileAccess(new AppFolders(_folder.Path), maxUploadBytes: 1000);
        using var content = new MemoryStream(new byte[1000]);

        var path = await files.SaveUploadAsync("logo.png", content, Token);

        var hash = Convert.ToHexStringLower(System.Security.Cryptography.SHA256.HashData(new byte[1000]))[..16];
        Assert.Equal(Path.Combine(Images, hash, "logo.png"), path);
        Assert.Equal([path], Directory.GetFiles(Images, "*", SearchOption.AllDirectories));
        Assert.Equal(1000, new FileInfo(path).Length);
    }

    [Fact]
    public async Task SaveUpload_SameNameOtherBytes_BothKeptNeitherReplaced()
    {
        var files = new App.Services.FileAccess(new AppFolders(_folder.Path));

        var first = await files.SaveUploadAsync("same.png", new MemoryStream([1, 2, 3]), Token);
        var second = await files.SaveUploadAsync("same.png", new MemoryStream([4, 5, 6]), Token);
        var again = await files.SaveUploadAsync("same.png", new MemoryStream([1, 2, 3]), Token);

        Assert.NotEqual(first, second);
        Assert.Equal(first, again);
        Assert.Equal([1, 2, 3], await File.ReadAllBytesAsync(first, Token));
        Assert.Equal([4, 5, 6], await File.ReadAllBytesAsync(second, Token));
        Assert.Equal("same.png", Path.GetFileName(second));
    }

    [Fact]
    public async Task SaveUpload_InterlockRefusesAtTheEnd_NothingKeptAndTheEarlierFileUntouched()
    {
        var files = new App.Services.FileAccess(new AppFolders(_folder.Path));
        var earlier = await files.SaveUploadAsync("same.png", new MemoryStream([1, 2, 3]), Token);
        var before = Directory.GetFiles(Images, "*", SearchOption.AllDirectories);

        // The run started while the bytes came in: the interlock refuses when they are whole.
        await Assert.ThrowsAsync<MachineBusyException>(() => files.SaveUploadAsync(
            "same.png", new MemoryStream([4, 5, 6]), Token, () => throw new MachineBusyException("a run is under way: the job cannot change until it ends")));

        Assert.Equal(before, Directory.GetFiles(Images, "*", SearchOption.AllDirectories));
        Assert.Equal([1, 2, 3], await File.ReadAllBytesAsync(earlier, Token));
    }

    [Fact]
    public async Task SaveUpload_PastTheQuota_RefusedAndNothingKept()
    {
        var files = new App.Services.FileAccess(new AppFolders(_folder.Path), maxUploadBytes: 1000, quotaBytes: 1500);
        await files.SaveUploadAsync("first.png", new MemoryStream(new byte[1000]), Token);

        var error = await Assert.ThrowsAsync<UploadException>(() => files.SaveUploadAsync("second.png", new MemoryStream(new byte[600]), Token));

        Assert.True(error.QuotaExceeded);
        Assert.StartsWith("second.png: the image folder would hold more than", error.Message, StringComparison.Ordinal);
        Assert.Single(Directory.GetFiles(Images, "*", SearchOption.AllDirectories));
    }

    [Fact]
    public async Task RemoveUpload_AnUpload_FileAndItsFolderGoneAnythingElseLeftAlone()
    {
        var files = new App.Services.FileAccess(new AppFolders(_folder.Path));
        var path = await files.SaveUploadAsync("x.png", new MemoryStream([1]), Token);
        var outside = Path.Combine(_folder.Path, "settings.json");
        await File.WriteAllTextAsync(outside, "{}", Token);

        files.RemoveUpload(path);
        files.RemoveUpload(outside);

        Assert.Empty(Directory.GetFileSystemEntries(Images));
        Assert.True(File.Exists(outside));
    }

    /// <summary>Gives some bytes, then fails as a dropped connection does.</summary>
    private sealed class BreakingStream : MemoryStream
    {
        private int _reads;

        public override ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken = default) =>
            _reads++ == 0 ? ValueTask.FromResult(Math.Min(buffer.Length, 500)) : throw new IOException("the connection was reset");
    }
}
