// The QR through socat ptys against the twin attached in this process (on the wall clock, as `laserengrave simulator`
// in tools/ports-bench.sh), engraved by the CLI in another process N times; each run's recording replayed from its log
// alone and compared with the simulator's own burn, pixel for pixel.
//   dotnet build -c Release src/LaserEngrave.Cli && dotnet run -c Release --project tools/replay-ports-bench -- [N] [WIDTH_MM]
// Environment: CLI (laserengrave.dll; default this tree's Release build), LOOPS=1 (two CPU-busy loops meanwhile),
// MEASURE=0 (the default profile instead of one measured through the ptys first, as tools/ports-bench.sh), PIECES=3 (every
// reply in two pieces this many ms apart, as tools/ports-bench.sh's simulator; 0 or unset: whole), OUT.
using System.Diagnostics;
using System.Text.Json;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Testing;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Replay;
using LaserEngrave.Wire.Serial;

var n = args.Length > 0 ? int.Parse(args[0]) : 1;
var width = args.Length > 1 ? args[1] : "2";
var root = Path.GetFullPath(Path.Combine(AppContext.BaseDirectory, "../../../../.."));
var cli = Environment.GetEnvironmentVariable("CLI") ?? Path.Combine(root, "src/LaserEngrave.Cli/bin/Release/net10.0/laserengrave.dll");
var output = Environment.GetEnvironmentVariable("OUT") ?? Directory.CreateTempSubdirectory("replay-ports-bench.").FullName;
Directory.CreateDirectory(output);
var busy = new List<Process>();
if (Environment.GetEnvironmentVariable("LOOPS") == "1")
{
    for (var i = 0; i < 2; i++)
    {
        busy.Add(Process.Start(new ProcessStartInfo("bash", ["-c", "while :; do :; done"]))!);
    }
}

// The twin stands in for the devices and their adapters, which never wait for this computer: raised as `laserengrave
// simulator` raises itself (tools/ports-bench.sh's NICE=-10), where the computer allows it.
using var priority = LaserEngrave.Devices.Scheduling.RunPriority.Raise();
try
{
    var profile = LaserEngrave.Core.Geometry.MachineProfile.Default;
    var pieces = double.TryParse(Environment.GetEnvironmentVariable("PIECES"), System.Globalization.CultureInfo.InvariantCulture, out var gapMs) && gapMs > 0
        ? new LaserEngrave.Simulator.Serial.ReplyPieces(1, gapMs)
        : default;
    await using var stage = await SocatPtyPair.StartAsync(CancellationToken.None);
    await using var laser = await SocatPtyPair.StartAsync(CancellationToken.None);
    var simulator = SimulatedMachine.Attach(SerialPortLink.Open(stage.A, profile.StageBaudRate), SerialPortLink.Open(laser.A, profile.Gate.BaudRate), profile, new SimulatorOptions { StartMm = 1, ReplyPieces = pieces });
    await using (simulator)
    {
        var profilePath = Path.Combine(output, "profile.json");
        var measure = Environment.GetEnvironmentVariable("MEASURE") != "0";
        var (latencyExit, latencyOut, latencyError) = measure ? await RunCli(cli, "machine", "latency", "--stage-port", stage.B, "--laser-port", laser.B, "--profile", profilePath, "--write") : (0, "not measured (MEASURE=0): the default profile", string.Empty);
        Console.WriteLine($"latency measured (exit {latencyExit}): {string.Join(" | ", latencyOut.Split('\n').Where(l => l.Contains("adapter") || l.Contains("round trips")))}{latencyError.Split('\n').FirstOrDefault()}");
        for (var j = 1; j <= n; j++)
        {
            var inspector = new BurnInspector(simulator);
            inspector.Begin();
            var watch = Stopwatch.StartNew();
            string[] profileArguments = measure ? ["--profile", profilePath] : [];
            var (exit, json, error) = await RunCli(cli, ["engrave", Path.Combine(root, "assets/qr-code.bmp"), "--width-mm", width, "--origin-mm", "10,10", "--stage-port", stage.B, "--laser-port", laser.B,
                .. profileArguments, "--json", "--log-dir", Path.Combine(output, "logs")]);
            var wall = watch.Elapsed.TotalSeconds;
            string logPath;
            try
            {
                using var document = JsonDocument.Parse(json);
                logPath = document.RootElement.GetProperty("logPath").GetString()!;
            }
            catch (Exception ex) when (ex is JsonException or KeyNotFoundException or InvalidOperationException)
            {
                Console.WriteLine($"job {j}: exit {exit}, no log ({error.Split('\n').FirstOrDefault()})");
                continue;
            }

            var record = RunLogStore.Read(logPath);
            var spec = RunReplay.ToJobSpec(record);
            var job = PreparedJob.Prepare(spec);
            await Task.Delay(TimeSpan.FromSeconds(2)); // the last burst's pulses, on the wall clock
            var simulated = inspector.Inspect(job);
            var simulatedBurn = inspector.Report!;
            var events = WireRecording.Read(Path.Combine(Path.GetDirectoryName(logPath)!, record.Recording!.File));
            var setup = RecordedRunReplay.Setup(record, spec.Profile, events, new SimulatorOptions());
            var (replayed, burn, uncertainty) = await RecordedRunReplay.ReplayWithUncertaintyAsync(job, spec.Profile, events, setup, CancellationToken.None);
            long differing = 0;
            for (var y = 0; y < burn!.Burned.Height; y++)
            {
                for (var x = 0; x < burn.Burned.Width; x++)
                {
                    differing += burn.Burned[x, y] != simulatedBurn.Burned[x, y] ? 1 : 0;
                }
            }

            Console.WriteLine($"job {j}: exit {exit} {record.Outcome} {record.Fault?.Message} wall {wall:0.0} s");
            Console.WriteLine($"  simulator: {simulated.Pulses} pulses, on white {simulated.LaserOnTravelCount}, extra {simulated.ExtraPixels}, missing {simulated.MissingPixels}, edges {simulated.Edges?.MeanErrorUm:0.00}/{simulated.Edges?.MaxErrorUm:0.00} µm");
            Console.WriteLine($"  replay:    {replayed.Pulses} pulses, on white {replayed.LaserOnTravelCount}, extra {replayed.ExtraPixels}, missing {replayed.MissingPixels}, edges {replayed.Edges?.MeanErrorUm:0.00}/{replayed.Edges?.MaxErrorUm:0.00} µm; pixels differing from the simulator's {differing}");
            Console.WriteLine($"  uncertain: {uncertainty?.Summary()}");
        }
    }
}
finally
{
    foreach (var p in busy)
    {
        p.Kill();
    }
}

static async Task<(int Exit, string Output, string Error)> RunCli(string cli, params string[] arguments)
{
    var start = new ProcessStartInfo("dotnet") { RedirectStandardOutput = true, RedirectStandardError = true, UseShellExecute = false };
    start.ArgumentList.Add(cli);
    foreach (var a in arguments)
    {
        start.ArgumentList.Add(a);
    }

    using var process = Process.Start(start)!;
    var output = process.StandardOutput.ReadToEndAsync();
    var error = process.StandardError.ReadToEndAsync();
    await process.WaitForExitAsync();
    return (process.ExitCode, await output, await error);
}
