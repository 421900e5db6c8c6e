using System.CommandLine;
using System.Diagnostics;
using System.Globalization;
using LaserEngrave.Cli.Commands;

namespace LaserEngrave.Cli.Tests;

/// <summary>A decimal comma reads as a decimal mark in every number option, never as a thousands separator, in every locale.</summary>
public class DecimalCommaTests
{
    private static string Qr => Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");

    [Theory]
    [InlineData("5,5", "5.5 x 5.5 mm")]
    [InlineData("0,5", "0.5 x 0.5 mm")]
    [InlineData("5.5", "5.5 x 5.5 mm")]
    public async Task Plan_WidthWithDecimalMark_ThatWidth(string width, string size)
    {
        var (exit, stdout, stderr) = await CliHarness.RunAsync("plan", Qr, "--width-mm", width);

        Assert.True(exit == 0, stderr);
        Assert.Contains(size, stdout, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("10,10", "origin 10, 10 mm")]
    [InlineData("5.5,10.2", "origin 5.5, 10.2 mm")]
    [InlineData("5,5;10,2", "origin 5.5, 10.2 mm")]
    public async Task Plan_OriginPair_ReadOneWayOnly(string origin, string expected)
    {
        var (exit, stdout, stderr) = await CliHarness.RunAsync("plan", Qr, "--width-mm", "5", "--origin-mm", origin);

        Assert.True(exit == 0, stderr);
        Assert.Contains(expected, stdout, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("--origin-mm", "5,5,10,2", "--origin-mm 5,5,10,2: could be read more than one way; write X,Y with decimal points (5.5,10.2) or X;Y with decimal commas (5,5;10,2)")]
    [InlineData("--width-mm", "1.000,5", "--width-mm 1.000,5: has more than one decimal mark")]
    [InlineData("--width-mm", "1,000,000", "--width-mm 1,000,000: has more than one decimal mark")]
    [InlineData("--pulses-per-dot", "1,5", "--pulses-per-dot 1,5: takes a whole number")]
    public async Task Plan_AmbiguousNumber_RefusedWithHowToWriteIt(string option, string value, string message)
    {
        var (exit, stdout, stderr) = await CliHarness.RunAsync(option == "--width-mm" ? ["plan", Qr, option, value] : ["plan", Qr, "--width-mm", "5", "--mode", "dots", option, value]);

        Assert.Equal(2, exit);
        Assert.Contains(message, stderr, StringComparison.Ordinal);
        Assert.Single(stderr.TrimEnd().Split('\n'));
        Assert.Equal(string.Empty, stdout);
    }

    [Theory]
    [InlineData("--frequency-hz", "1,000", "--frequency-hz 1,000: could be 1 or 1000: write 1000 or 1.0")]
    [InlineData("--frequency-hz", "1.000", "--frequency-hz 1.000: could be 1 or 1000: write 1000 or 1.0")]
    [InlineData("--frequency-hz", "10,000", "--frequency-hz 10,000: could be 10 or 10000: write 10000 or 10.0")]
    [InlineData("--frequency-hz", "2,500", "--frequency-hz 2,500: could be 2.5 or 2500: write 2500 or 2.5")]
    [InlineData("--width-mm", "1,000", "--width-mm 1,000: could be 1 or 1000: write 1000 or 1.0")]
    [InlineData("--origin-mm", "1.000,2.000", "--origin-mm 1.000,2.000: X '1.000' could be 1 or 1000: write 1000 or 1.0")]
    public async Task Plan_ThousandsOrDecimals_RefusedNamingBothReadings(string option, string value, string message)
    {
        var (exit, stdout, stderr) = await CliHarness.RunAsync(option == "--width-mm" ? ["plan", Qr, option, value] : ["plan", Qr, "--width-mm", "5", option, value]);

        Assert.Equal(2, exit);
        Assert.Contains(message, stderr, StringComparison.Ordinal);
        Assert.Single(stderr.TrimEnd().Split('\n'));
        Assert.Equal(string.Empty, stdout);
    }

    [Theory]
    // Whole hertz only (the gate is sent whole Hz), so the decimal comma is shown on a whole number.
    [InlineData("2500,0", "\"pulseSpacingUm\": 0.4,")]
    [InlineData("1250,00", "\"pulseSpacingUm\": 0.8,")]
    [InlineData("1000", "\"pulseSpacingUm\": 1,")]
    public async Task Plan_FrequencyWithOneReading_ReadAtTheDefaultSpeedOf1MmPerS(string value, string expected)
    {
        var (exit, stdout, stderr) = await CliHarness.RunAsync("plan", Qr, "--width-mm", "5", "--frequency-hz", value, "--json");

        Assert.True(exit == 0, stderr);
        Assert.Contains(expected, stdout, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Process_SpeedWithDecimalComma_HalfAMillimetrePerSecond()
    {
        var (exit, stdout, stderr) = await CliHarness.RunAsync("plan", Qr, "--width-mm", "5", "--speed-mm-s", "0,5", "--json");

        Assert.True(exit == 0, stderr);
        Assert.Contains("\"pulseSpacingUm\": 0.5,", stdout, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("Cannot parse argument 'x' for option '--width-mm' as expected type 'System.Nullable`1[System.Double]'.", "--width-mm x: not a number")]
    [InlineData("Cannot parse argument 'maybe' for option '--invert' as expected type 'System.Boolean'.", "--invert maybe: not true or false")]
    [InlineData("Cannot parse argument '1,5' for argument 'HZ' as expected type 'System.Int32'.", "HZ 1,5: not a whole number")]
    public void UserWords_SystemCommandLineTypeName_InTheUsersWords(string message, string expected)
    {
        Assert.Equal(expected, CliRunner.UserWords(message));
    }

    [Fact]
    public void EveryNumberOptionAndArgument_ReadByNumberText()
    {
        var unread = new List<string>();
        void Walk(Command command)
        {
            foreach (var symbol in command.Options.Cast<Symbol>().Concat(command.Arguments))
            {
                var type = symbol is Option o ? o.ValueType : ((Argument)symbol).ValueType;
                var inner = Nullable.GetUnderlyingType(type) ?? type.GetElementType() ?? type;
                if (inner.IsPrimitive && inner != typeof(bool) || inner == typeof(decimal))
                {
                    if (symbol.GetType().GetProperty("CustomParser")?.GetValue(symbol) is null)
                    {
                        unread.Add($"{command.Name} {symbol.Name}");
                    }
                }
            }

            foreach (var sub in command.Subcommands)
            {
                Walk(sub);
            }
        }

        Walk(Program.BuildRoot());

        Assert.Empty(unread);
    }

    [Theory]
    [InlineData("de_DE.UTF-8")]
    [InlineData("es_AR.UTF-8")]
    [InlineData("fr_FR.UTF-8")]
    [InlineData("en_US.UTF-8")]
    public async Task Process_UnderALocale_DecimalCommaIsADecimalMark(string lang)
    {
        var dotnet = Environment.GetEnvironmentVariable("DOTNET_HOST_PATH") is { Length: > 0 } host ? host : "dotnet";
        var start = new ProcessStartInfo(dotnet)
        {
            ArgumentList = { typeof(Program).Assembly.Location, "plan", Qr, "--width-mm", "5,5", "--origin-mm", "1,5;2,25" },
            RedirectStandardOutput = true,
            RedirectStandardError = true,
            UseShellExecute = false,
            Environment = { ["LANG"] = lang, ["LC_ALL"] = lang },
        };
        using var process = Process.Start(start)!;
        var stdout = await process.StandardOutput.ReadToEndAsync(TestContext.Current.CancellationToken);
        var stderr = await process.StandardError.ReadToEndAsync(TestContext.Current.CancellationToken);
        await process.WaitForExitAsync(TestContext.Current.CancellationToken);

        Assert.True(process.ExitCode == 0, stderr);
        Assert.Contains("5.5 x 5.5 mm at origin 1.5, 2.25 mm", stdout, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("de-DE")]
    [InlineData("en-US")]
    public async Task Plan_UnderACurrentCulture_SameReading(string name)
    {
        var culture = (CultureInfo)CultureInfo.InvariantCulture.Clone();
        (culture.NumberFormat.NumberDecimalSeparator, culture.NumberFormat.NumberGroupSeparator) = name == "de-DE" ? (",", ".") : (".", ",");
        var before = CultureInfo.CurrentCulture;
        CultureInfo.CurrentCulture = culture;
        try
        {
            var (exit, stdout, stderr) = await CliHarness.RunAsync("plan", Qr, "--width-mm", "5,5");

            Assert.True(exit == 0, stderr);
            Assert.Contains("5.5 x 5.5 mm", stdout, StringComparison.Ordinal);
        }
        finally
        {
            CultureInfo.CurrentCulture = before;
        }
    }
}
