using System.CommandLine;
using LaserEngrave.Cli.Commands;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Cli;

/// <summary>Bad input or options: exit code 2.</summary>
internal sealed class UsageException(string message) : Exception(message);

/// <summary>Runs the parsed command and turns every failure into one line on stderr and an exit code.</summary>
/// <remarks>Exit codes: 0 success, 2 bad input or options, 1 any other failure.</remarks>
internal static class CliRunner
{
    public const int Ok = 0;
    public const int Failure = 1;
    public const int BadInput = 2;

    public static async Task<int> InvokeAsync(RootCommand root, string[] args, TextWriter stdout, TextWriter stderr, CancellationToken cancellationToken = default)
    {
        var parse = root.Parse(args);
        if (parse.Errors.Count > 0)
        {
            // An unknown word says more than the "required command was not provided" that comes with it.
            var error = parse.Errors.FirstOrDefault(e => e.Message.StartsWith("Unrecognized", StringComparison.Ordinal)) ?? parse.Errors[0];
            stderr.WriteLine($"laserengrave: {error.Message} (see --help)");
            return BadInput;
        }

        var config = new InvocationConfiguration
        {
            Output = stdout,
            Error = stderr,
            EnableDefaultExceptionHandler = false,

            // Ctrl+C cancels the command's token; a run then needs time to switch the laser off, stop the stage and
            // write its log before the process may end (the default is 2 s).
            ProcessTerminationTimeout = TimeSpan.FromSeconds(30),
        };
        try
        {
            return await parse.InvokeAsync(config, cancellationToken).ConfigureAwait(false);
        }
        catch (Exception ex) when (ex is not OutOfMemoryException)
        {
            var verbose = parse.GetValue(CliOptions.Verbose);
            stderr.WriteLine($"laserengrave: {OneLine(ex)}");
            if (verbose)
            {
                stderr.WriteLine(ex.ToString());
            }

            return ExitCodeFor(ex);
        }
    }

    public static int ExitCodeFor(Exception ex) => ex switch
    {
        UsageException or InvalidDataException or ProfileException or RunLogException or GeometryException or PlanException or ArgumentException or FormatException => BadInput,
        _ when ex.GetType().Name == "ImageLoadException" => BadInput,
        Core.Vectors.DrawingException => BadInput,
        Core.Sweeps.SweepException => BadInput,
        TestMoveException => BadInput,
        DeviceException => Failure,
        OperationCanceledException => Failure,
        _ => Failure,
    };

    private static string OneLine(Exception ex) => ex.Message.ReplaceLineEndings(" ");
}
