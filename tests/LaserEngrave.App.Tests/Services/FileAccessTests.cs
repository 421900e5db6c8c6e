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
    public async Task SaveUpload_AtTheLimit_KeptUnderItsName()
    {
        var files = new App.Services.FileAccess(new AppFolders(_folder.Path), maxUploadBytes: 1000);
        using var content = new MemoryStream(new byte[1000]);

        var path = await files.SaveUploadAsync("../../etc/logo.png", content, Token);

        Assert.Equal(Path.Combine(Images, "logo.png"), path);
        Assert.Equal([path], Directory.GetFiles(Images));
        Assert.Equal(1000, new FileInfo(path).Length);
    }

    /// <summary>Gives some bytes, then fails as a dropped connection does.</summary>
    private sealed class BreakingStream : MemoryStream
    {
        private int _reads;

        public override ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken = default) =>
            _reads++ == 0 ? ValueTask.FromResult(Math.Min(buffer.Length, 500)) : throw new IOException("the connection was reset");
    }
}
