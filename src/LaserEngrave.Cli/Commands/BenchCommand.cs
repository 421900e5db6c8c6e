using System.Buffers.Binary;
using System.CommandLine;
using System.Diagnostics;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave bench`: load, mask and plan a large 1-bit BMP and print the times and peak memory.</summary>
/// <remarks>BenchmarkDotNet (bench/) measures planning alone; this measures the whole path in one process, peak memory included.</remarks>
internal static class BenchCommand
{
    public static Command Create()
    {
        var size = new Option<int>("--size") { Description = "Side of the square test image in pixels", DefaultValueFactory = _ => 20000 };
        var image = new Option<string?>("--image") { Description = "Use this image instead of a generated one" };
        var command = new Command("bench", "Time load + mask + plan statistics of a large 1-bit BMP (default 20000 x 20000) and report peak memory") { size, image };
        command.SetAction(result =>
        {
            var output = result.InvocationConfiguration.Output;
            var side = result.GetValue(size);
            if (side is < 64 or > 60000)
            {
                throw new UsageException($"--size {side}: must be between 64 and 60000");
            }

            var path = result.GetValue(image);
            var generated = path is null;
            if (path is null)
            {
                path = Path.Combine(Path.GetTempPath(), $"laserengrave-bench-{side}.bmp");
                WriteQrLikeBmp(path, side, side);
                output.WriteLine(string.Create(CultureInfo.InvariantCulture, $"Generated {path} ({new FileInfo(path).Length / 1e6:0.0} MB)"));
            }

            try
            {
                Run(path, output);
            }
            finally
            {
                if (generated)
                {
                    File.Delete(path);
                }
            }

            return 0;
        });
        return command;
    }

    private static void Run(string path, TextWriter output)
    {
        GC.Collect();
        var total = Stopwatch.StartNew();
        var mask = MaskBuilder.FromFile(path, MaskOptions.Default, out var info);
        var loadSeconds = total.Elapsed.TotalSeconds;

        var spec = new JobSpec { ImagePath = path, Size = SizeSpec.Width(50) };
        var planTimer = Stopwatch.StartNew();
        var job = PreparedJob.Prepare(spec, info, mask);
        var planSeconds = planTimer.Elapsed.TotalSeconds;
        var totalSeconds = total.Elapsed.TotalSeconds;

        // A second planning pass, warm, is the figure for planning alone.
        var warm = Stopwatch.StartNew();
        var again = job.Plan.ComputeStatistics(spec.Process, spec.Profile.Gate);
        var warmSeconds = warm.Elapsed.TotalSeconds;

        var pixels = (double)mask.Width * mask.Height;
        var peakMb = Process.GetCurrentProcess().PeakWorkingSet64 / 1e6;
        var c = CultureInfo.InvariantCulture;
        output.WriteLine(string.Create(c, $"Image:                 {info.Width} x {info.Height} px, {info.BitsPerPixel} bit {info.Format}"));
        output.WriteLine(string.Create(c, $"Load + mask:           {loadSeconds:0.000} s"));
        output.WriteLine(string.Create(c, $"Plan statistics:       {planSeconds:0.000} s ({again.BurnRuns} burn runs, {again.Moves} moves)"));
        output.WriteLine(string.Create(c, $"Load + mask + plan:    {totalSeconds:0.000} s (goal: under 1.5 s)"));
        output.WriteLine(string.Create(c, $"Planning alone (warm): {warmSeconds:0.000} s = {pixels / warmSeconds / 1e9:0.00} gigapixels/s (goal: 1.5 or more)"));
        output.WriteLine(string.Create(c, $"Peak memory:           {peakMb:0} MB (goal: under 300 MB)"));
    }

    /// <summary>Writes a 1-bit bottom-up BMP of QR-like 41 x 41 modules, row by row so the benchmark's memory is the reader's alone.</summary>
    internal static void WriteQrLikeBmp(string path, int width, int height)
    {
        const int Modules = 41;
        var stride = ((width + 31) / 32) * 4;
        var random = new Random(41);
        var cells = new bool[Modules, Modules];
        for (var y = 0; y < Modules; y++)
        {
            for (var x = 0; x < Modules; x++)
            {
                cells[x, y] = random.Next(2) == 1;
            }
        }

        using var file = new FileStream(path, FileMode.Create, FileAccess.Write, FileShare.None, 1 << 16);
        Span<byte> header = stackalloc byte[62];
        header.Clear();
        header[0] = (byte)'B';
        header[1] = (byte)'M';
        BinaryPrimitives.WriteInt32LittleEndian(header[2..], 62 + (stride * height));
        BinaryPrimitives.WriteInt32LittleEndian(header[10..], 62);
        BinaryPrimitives.WriteInt32LittleEndian(header[14..], 40);
        BinaryPrimitives.WriteInt32LittleEndian(header[18..], width);
        BinaryPrimitives.WriteInt32LittleEndian(header[22..], height);
        BinaryPrimitives.WriteInt16LittleEndian(header[26..], 1);
        BinaryPrimitives.WriteInt16LittleEndian(header[28..], 1);
        BinaryPrimitives.WriteInt32LittleEndian(header[34..], stride * height);
        BinaryPrimitives.WriteInt32LittleEndian(header[46..], 2);

        // Palette: index 0 black, index 1 white.
        header[58] = 255;
        header[59] = 255;
        header[60] = 255;
        file.Write(header);

        var row = new byte[stride];
        for (var fileRow = 0; fileRow < height; fileRow++)
        {
            var y = height - 1 - fileRow;
            var my = (int)((long)y * Modules / height);
            Array.Clear(row);
            for (var x = 0; x < width; x++)
            {
                var black = cells[(int)((long)x * Modules / width), my];
                if (!black)
                {
                    row[x >> 3] |= (byte)(0x80 >> (x & 7));
                }
            }

            file.Write(row);
        }
    }
}
