using System.Diagnostics;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.IO;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Core.Tests.IO;

public class RegularFileTests
{
    [Fact]
    public void Problem_RegularFileOrMissing_IsNull()
    {
        var path = Path.GetTempFileName();
        try
        {
            Assert.Null(RegularFile.Problem(path));
            Assert.Null(RegularFile.Problem(path + ".missing"));
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Problem_FolderAndDevice_SayWhatTheyAre()
    {
        Assert.Equal("is a folder, not a file", RegularFile.Problem(Path.GetTempPath()));
        Assert.Equal("is a character device, not a regular file", RegularFile.Problem("/dev/null"));
    }

    [Fact]
    public void Readers_Fifo_RefusedWithoutBlocking()
    {
        var fifo = MakeFifo();
        try
        {
            Assert.Equal("is a named pipe (FIFO), not a regular file", RegularFile.Problem(fifo));

            // Each would block for ever in open() without the check; none of them may get that far.
            Assert.Contains("named pipe", Assert.Throws<ImageLoadException>(() => ImageLoader.ReadInfo(fifo)).Message, StringComparison.Ordinal);
            Assert.Contains("named pipe", Assert.Throws<ProfileException>(() => MachineProfile.Load(fifo)).Message, StringComparison.Ordinal);
            Assert.Contains("named pipe", Assert.Throws<RunLogException>(() => RunLogStore.Read(fifo)).Message, StringComparison.Ordinal);
            Assert.Contains("named pipe", Assert.Throws<ImageLoadException>(() => LaserEngrave.Core.Jobs.PreparedJob.HashFile(fifo)).Message, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(fifo);
        }
    }

    internal static string MakeFifo()
    {
        var path = Path.Combine(Path.GetTempPath(), $"le-fifo-{Guid.NewGuid():N}");
        using var mkfifo = System.Diagnostics.Process.Start(new ProcessStartInfo("mkfifo", path) { UseShellExecute = false })!;
        mkfifo.WaitForExit();
        Assert.Equal(0, mkfifo.ExitCode);
        return path;
    }
}
