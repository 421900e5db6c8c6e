using System.CommandLine;

namespace LaserEngrave.Cli.Commands;

/// <summary>Options shared by several commands.</summary>
internal static class CliOptions
{
    public static readonly Option<bool> Verbose = new("--verbose")
    {
        Description = "Print the full error (with stack trace) when something fails",
        Recursive = true,
    };
}
