using System.CommandLine;
using System.Runtime.InteropServices;
using LaserEngrave.Cli.Commands;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Wire.Serial;

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
            stderr.WriteLine($"laserengrave: {UserWords(error.Message)}{DidYouMean(parse, error.Message)} (see --help)");
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
        // Ctrl+C and SIGTERM are System.CommandLine's: they cancel the command's token, and it waits for the command to end.
        // A hang-up (SIGHUP: a closed terminal or a dropped remote session; on Windows the console window closed) and
        // SIGQUIT (Windows: Ctrl+Break) do the same here: a run aborts, laser off first, stage stopped, log written.
        using var signalled = CancellationTokenSource.CreateLinkedTokenSource(cancellationToken);
        var ended = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
        using var hangUp = SignalAbort(PosixSignal.SIGHUP, signalled, ended.Task, config.ProcessTerminationTimeout.Value);
        using var quit = SignalAbort(PosixSignal.SIGQUIT, signalled, ended.Task, config.ProcessTerminationTimeout.Value);
        try
        {
            return await parse.InvokeAsync(config, signalled.Token).ConfigureAwait(false);
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
        finally
        {
            ended.TrySetResult();
        }
    }

    /// <summary>Turns <paramref name="signal"/> into the command's cancellation, as Ctrl+C is; null where the platform has no such signal.</summary>
    /// <remarks>
    /// The handler keeps the process until the command has ended (at most <paramref name="wait"/>): Windows ends a process
    /// once its console-close handler returns, so the run's abort and log must be done by then.
    /// </remarks>
    private static PosixSignalRegistration? SignalAbort(PosixSignal signal, CancellationTokenSource cancel, Task ended, TimeSpan wait)
    {
        if (OperatingSystem.IsAndroid() || OperatingSystem.IsIOS() || OperatingSystem.IsTvOS() || OperatingSystem.IsBrowser())
        {
            return null;
        }

        try
        {
            return PosixSignalRegistration.Create(signal, context =>
            {
                context.Cancel = true;
                try
                {
                    cancel.Cancel();
                }
                catch (ObjectDisposedException)
                {
                    // The command has ended already.
                    return;
                }

                if (OperatingSystem.IsWindows())
                {
                    _ = ended.Wait(wait, CancellationToken.None);
                }
            });
        }
        catch (PlatformNotSupportedException)
        {
            return null;
        }
    }

    public static int ExitCodeFor(Exception ex) => ex switch
    {
        UsageException or InvalidDataException or ProfileException or RunLogException or WireRecordingException or GeometryException or PlanException or ArgumentException or FormatException => BadInput,
        _ when ex.GetType().Name == "ImageLoadException" => BadInput,
        Core.Vectors.DrawingException => BadInput,
        Core.Sweeps.SweepException => BadInput,
        Core.Marks.MarkException => BadInput,
        TestMoveException => BadInput,
        DeviceException => Failure,
        OperationCanceledException => Failure,
        _ => Failure,
    };

    private static string OneLine(Exception ex) => ex.Message.ReplaceLineEndings(" ");

    /// <summary>System.CommandLine's "as expected type 'System.Nullable`1[System.Double]'" in the user's words.</summary>
    internal static string UserWords(string message)
    {
        var match = System.Text.RegularExpressions.Regex.Match(message, @"^Cannot parse argument '(?<value>.*)' for (option|argument) '(?<name>[^']*)' as expected type '(?<type>[^']*)'");
        if (!match.Success)
        {
            return message;
        }

        var type = match.Groups["type"].Value;
        var what = type.Contains("Boolean", StringComparison.Ordinal) ? "true or false"
            : type.Contains("Int", StringComparison.Ordinal) ? "a whole number"
            : type.Contains("Double", StringComparison.Ordinal) || type.Contains("Single", StringComparison.Ordinal) || type.Contains("Decimal", StringComparison.Ordinal) ? "a number"
            : "a value it takes";
        return $"{match.Groups["name"].Value} {match.Groups["value"].Value}: not {what}";
    }

    /// <summary>For an unknown word, the nearest command or option of the command it was typed in (" (did you mean plan?)"), or nothing.</summary>
    private static string DidYouMean(ParseResult parse, string message)
    {
        var match = System.Text.RegularExpressions.Regex.Match(message, "^Unrecognized command or argument '(?<word>[^']+)'");
        if (!match.Success)
        {
            return string.Empty;
        }

        var word = match.Groups["word"].Value;
        var command = parse.CommandResult.Command;
        var candidates = word.StartsWith('-')
            ? command.Options.Where(o => !o.Hidden).SelectMany(o => o.Aliases.Prepend(o.Name))
            : command.Subcommands.Where(c => !c.Hidden).SelectMany(c => c.Aliases.Prepend(c.Name));
        var best = candidates
            .Select(name => (Name: name, Distance: EditDistance(word, name)))
            .Where(c => c.Distance <= Math.Max(1, word.Length / 3))
            .OrderBy(c => c.Distance)
            .ThenBy(c => c.Name, StringComparer.Ordinal)
            .FirstOrDefault();
        return best.Name is null ? string.Empty : $" (did you mean {best.Name}?)";
    }

    /// <summary>Levenshtein distance, a swap of two neighbouring letters counted as one edit.</summary>
    private static int EditDistance(string a, string b)
    {
        var d = new int[a.Length + 1, b.Length + 1];
        for (var i = 0; i <= a.Length; i++)
        {
            d[i, 0] = i;
        }

        for (var j = 0; j <= b.Length; j++)
        {
            d[0, j] = j;
        }

        for (var i = 1; i <= a.Length; i++)
        {
            for (var j = 1; j <= b.Length; j++)
            {
                var cost = char.ToLowerInvariant(a[i - 1]) == char.ToLowerInvariant(b[j - 1]) ? 0 : 1;
                d[i, j] = Math.Min(Math.Min(d[i - 1, j] + 1, d[i, j - 1] + 1), d[i - 1, j - 1] + cost);
                if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                {
                    d[i, j] = Math.Min(d[i, j], d[i - 2, j - 2] + 1);
                }
            }
        }

        return d[a.Length, b.Length];
    }
}
