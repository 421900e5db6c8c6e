using System.Globalization;
using System.Text;

namespace LaserEngrave.Simulator.Faults;

/// <summary>One fault to inject: what, on which device, after how many commands or replies, how often.</summary>
/// <remarks>
/// Error, Silent and Disconnect count the commands the target receives; DropReply, Corrupt, Delay and NoAck count its
/// replies to commands (unsolicited ones such as Move Tracking are not counted). A broadcast frame is one command, and
/// one reply, per device that answers it. The grammar is in <see cref="FaultInjector.Parse"/>.
/// </remarks>
/// <param name="Kind">What the fault does.</param>
/// <param name="Target">The stage or the gate.</param>
public sealed record FaultRule(FaultKind Kind, FaultTarget Target)
{
    private static readonly string[] KindNames = ["drop-reply", "corrupt", "delay", "error", "silent", "disconnect", "no-ack"];

    /// <summary>Commands or replies let through untouched before the fault strikes.</summary>
    public int After { get; init; }

    /// <summary>How many commands or replies the fault affects; null for the kind's default (<see cref="EffectiveCount"/>).</summary>
    public int? Count { get; init; }

    /// <summary>Extra time before a delayed reply leaves.</summary>
    public int DelayMs { get; init; } = 500;

    /// <summary>Error code of an Error fault; null for 255 (Busy) on the stage, 1 on the gate.</summary>
    public int? Code { get; init; }

    /// <summary>Index of the reply byte a Corrupt fault inverts.</summary>
    public int ByteIndex { get; init; } = 1;

    /// <summary>Only this Zaber device number (stage faults); null for every device.</summary>
    public byte? Device { get; init; }

    /// <summary>Only commands, or replies, with this Zaber command number (stage faults, e.g. 60 Return Current Position); null for every one.</summary>
    public byte? Command { get; init; }

    /// <summary>Affected count: <see cref="Count"/>, else every one from then on for Silent and NoAck, else 1.</summary>
    public int EffectiveCount => Count ?? (Kind is FaultKind.Silent or FaultKind.NoAck ? int.MaxValue : 1);

    /// <summary>The error code an Error fault answers with.</summary>
    public int EffectiveCode => Code ?? (Target == FaultTarget.Stage ? 255 : 1);

    /// <summary>Whether the fault counts commands (true) or replies (false).</summary>
    public bool CountsCommands => Kind is FaultKind.Error or FaultKind.Silent or FaultKind.Disconnect;

    /// <summary>Parses one rule, e.g. <c>error:stage:code=20:after=3</c>; throws <see cref="FormatException"/> naming the problem.</summary>
    public static FaultRule Parse(string text)
    {
        ArgumentNullException.ThrowIfNull(text);
        var parts = text.Trim().Split(':');
        if (parts.Length < 2)
        {
            throw Bad(text, "expected kind:target[:key=value...]");
        }

        var kindIndex = Array.IndexOf(KindNames, parts[0].Trim().ToLowerInvariant());
        if (kindIndex < 0)
        {
            throw Bad(text, $"unknown kind '{parts[0]}' (expected {string.Join(", ", KindNames)})");
        }

        var kind = (FaultKind)kindIndex;
        var target = parts[1].Trim().ToLowerInvariant() switch
        {
            "stage" => FaultTarget.Stage,
            "gate" or "laser" => FaultTarget.Gate,
            _ => throw Bad(text, $"unknown target '{parts[1]}' (expected stage or gate)"),
        };
        if (kind == FaultKind.NoAck && target != FaultTarget.Gate)
        {
            throw Bad(text, "no-ack applies to the gate only (use drop-reply for the stage)");
        }

        var rule = new FaultRule(kind, target);
        foreach (var part in parts.Skip(2))
        {
            var eq = part.IndexOf('=', StringComparison.Ordinal);
            if (eq <= 0)
            {
                throw Bad(text, $"'{part}' is not key=value");
            }

            var key = part[..eq].Trim().ToLowerInvariant();
            var value = part[(eq + 1)..].Trim();
            rule = key switch
            {
                "after" => rule with { After = Number(text, key, value, 0, int.MaxValue) },
                "count" when kind is FaultKind.Silent => throw Bad(text, "silent lasts for good and takes no count"),
                "count" => rule with { Count = value.Equals("all", StringComparison.OrdinalIgnoreCase) ? int.MaxValue : Number(text, key, value, 1, int.MaxValue) },
                "ms" when kind == FaultKind.Delay => rule with { DelayMs = Number(text, key, value, 0, 3_600_000) },
                "code" when kind == FaultKind.Error => rule with { Code = Number(text, key, value, target == FaultTarget.Stage ? int.MinValue : 0, int.MaxValue) },
                "byte" when kind == FaultKind.Corrupt => rule with { ByteIndex = Number(text, key, value, 0, 255) },
                "device" when target == FaultTarget.Stage => rule with { Device = (byte)Number(text, key, value, 1, 254) },
                "command" when target == FaultTarget.Stage => rule with { Command = (byte)Number(text, key, value, 0, 255) },
                _ => throw Bad(text, $"'{key}' does not apply to {KindNames[kindIndex]}:{parts[1].Trim()}"),
            };
        }

        return rule;
    }

    /// <summary>The rule in the spec grammar, so it can be parsed back.</summary>
    public override string ToString()
    {
        var text = new StringBuilder(KindNames[(int)Kind]).Append(':').Append(Target == FaultTarget.Stage ? "stage" : "gate");
        Append("device", Device?.ToString(CultureInfo.InvariantCulture));
        Append("command", Command?.ToString(CultureInfo.InvariantCulture));
        Append("after", After == 0 ? null : After.ToString(CultureInfo.InvariantCulture));
        Append("count", Count switch { null => null, int.MaxValue => "all", var n => n.Value.ToString(CultureInfo.InvariantCulture) });
        Append("ms", Kind == FaultKind.Delay ? DelayMs.ToString(CultureInfo.InvariantCulture) : null);
        Append("code", Kind == FaultKind.Error ? EffectiveCode.ToString(CultureInfo.InvariantCulture) : null);
        Append("byte", Kind == FaultKind.Corrupt ? ByteIndex.ToString(CultureInfo.InvariantCulture) : null);
        return text.ToString();

        void Append(string key, string? value)
        {
            if (value is not null)
            {
                text.Append(':').Append(key).Append('=').Append(value);
            }
        }
    }

    private static int Number(string text, string key, string value, int min, int max)
    {
        if (!int.TryParse(value, NumberStyles.Integer, CultureInfo.InvariantCulture, out var n) || n < min || n > max)
        {
            throw Bad(text, $"{key}={value} is not a whole number in {min}..{max}");
        }

        return n;
    }

    private static FormatException Bad(string text, string why) => new($"fault '{text.Trim()}': {why}");
}
