namespace LaserEngrave.Simulator.Faults;

/// <summary>The faults the simulated machine injects; rules can be added and cleared while it runs.</summary>
/// <remarks>
/// Spec grammar (the CLI's <c>--fault</c>), rules separated by commas:
/// <code>
/// spec  := rule ("," rule)*
/// rule  := kind ":" target (":" key "=" value)*
/// kind  := drop-reply | corrupt | delay | error | silent | disconnect | no-ack
/// target:= stage | gate            ("laser" is accepted for gate)
/// keys  := after=N                 commands/replies let through first (default 0)
///          count=N | count=all     how many are affected (default 1; silent and no-ack: all)
///          ms=N                    delay only: extra time before the reply leaves (default 500)
///          code=N                  error only: the error code (default 255 Busy on the stage, 1 on the gate)
///          byte=N                  corrupt only: index of the reply byte inverted (default 1)
///          device=N                stage only: just this Zaber device number
///          command=N               stage only: just commands (or replies) with this Zaber command number
/// </code>
/// Example: <c>drop-reply:stage:after=10,error:stage:code=20:after=3,no-ack:gate:after=4</c>.
/// </remarks>
public sealed class FaultInjector
{
    private readonly Lock _lock = new();
    private readonly List<RuleState> _rules = [];
    private readonly List<(FaultTarget Target, byte? Device)> _silenced = [];

    /// <summary>Raised (on the simulator's thread) every time a rule strikes.</summary>
    public event EventHandler<FaultRule>? Triggered;

    public IReadOnlyList<FaultRule> Rules
    {
        get
        {
            lock (_lock)
            {
                return [.. _rules.Select(r => r.Rule)];
            }
        }
    }

    /// <summary>How many times any rule has struck.</summary>
    public int TriggeredCount { get; private set; }

    /// <summary>An injector holding the rules of <paramref name="spec"/> (none when it is null or blank).</summary>
    public static FaultInjector Parse(string? spec)
    {
        var injector = new FaultInjector();
        injector.Add(spec);
        return injector;
    }

    /// <summary>The rules of a comma-separated spec; throws <see cref="FormatException"/> naming the bad rule.</summary>
    public static IReadOnlyList<FaultRule> ParseRules(string? spec) =>
        string.IsNullOrWhiteSpace(spec)
            ? []
            : [.. spec.Split(',', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries).Select(FaultRule.Parse)];

    public void Add(FaultRule rule)
    {
        ArgumentNullException.ThrowIfNull(rule);
        lock (_lock)
        {
            _rules.Add(new RuleState(rule));
        }
    }

    /// <summary>Adds every rule of a spec.</summary>
    public void Add(string? spec)
    {
        foreach (var rule in ParseRules(spec))
        {
            Add(rule);
        }
    }

    /// <summary>Removes every rule and lifts every silence.</summary>
    public void Clear()
    {
        lock (_lock)
        {
            _rules.Clear();
            _silenced.Clear();
        }
    }

    /// <summary>Whether a Silent fault has struck <paramref name="device"/> of <paramref name="target"/>.</summary>
    public bool IsSilent(FaultTarget target, byte device = 0)
    {
        lock (_lock)
        {
            return _silenced.Exists(s => s.Target == target && (s.Device is null || s.Device == device));
        }
    }

    /// <summary>Decides what happens to a command <paramref name="device"/> of <paramref name="target"/> just received.</summary>
    internal CommandFault OnCommand(FaultTarget target, byte device = 0, byte? command = null)
    {
        var fault = default(CommandFault);
        var struck = new List<FaultRule>();
        lock (_lock)
        {
            if (_silenced.Exists(s => s.Target == target && (s.Device is null || s.Device == device)))
            {
                return new CommandFault(Ignore: true, null, false);
            }

            foreach (var state in _rules)
            {
                if (!state.Rule.CountsCommands || !state.Strikes(target, device, command))
                {
                    continue;
                }

                struck.Add(state.Rule);
                switch (state.Rule.Kind)
                {
                    case FaultKind.Silent:
                        _silenced.Add((target, state.Rule.Device));
                        fault = fault with { Ignore = true };
                        break;
                    case FaultKind.Disconnect:
                        fault = fault with { Disconnect = true };
                        break;
                    default:
                        fault = fault with { RefuseCode = state.Rule.EffectiveCode };
                        break;
                }
            }

            TriggeredCount += struck.Count;
        }

        Raise(struck);
        return fault;
    }

    /// <summary>Decides what happens to a reply to a command that <paramref name="device"/> of <paramref name="target"/> is about to send.</summary>
    internal ReplyFault OnReply(FaultTarget target, byte device = 0, byte? command = null)
    {
        var fault = default(ReplyFault);
        var struck = new List<FaultRule>();
        lock (_lock)
        {
            if (_silenced.Exists(s => s.Target == target && (s.Device is null || s.Device == device)))
            {
                return new ReplyFault(Drop: true, null, TimeSpan.Zero);
            }

            foreach (var state in _rules)
            {
                if (state.Rule.CountsCommands || !state.Strikes(target, device, command))
                {
                    continue;
                }

                struck.Add(state.Rule);
                fault = state.Rule.Kind switch
                {
                    FaultKind.Corrupt => fault with { CorruptByte = state.Rule.ByteIndex },
                    FaultKind.Delay => fault with { Delay = fault.Delay + TimeSpan.FromMilliseconds(state.Rule.DelayMs) },
                    _ => fault with { Drop = true },
                };
            }

            TriggeredCount += struck.Count;
        }

        Raise(struck);
        return fault;
    }

    private void Raise(List<FaultRule> struck)
    {
        foreach (var rule in struck)
        {
            Triggered?.Invoke(this, rule);
        }
    }

    /// <summary>A rule and how many events it has seen and struck.</summary>
    private sealed class RuleState(FaultRule rule)
    {
        private long _seen;
        private long _struck;

        public FaultRule Rule { get; } = rule;

        // Counts the event if it is the rule's, and says whether the rule strikes it.
        public bool Strikes(FaultTarget target, byte device, byte? command)
        {
            if (Rule.Target != target || (Rule.Device is { } only && only != device) || (Rule.Command is { } just && just != command))
            {
                return false;
            }

            _seen++;
            if (_seen <= Rule.After || _struck >= Rule.EffectiveCount)
            {
                return false;
            }

            _struck++;
            return true;
        }
    }
}

/// <summary>What to do with a received command: carry it out, ignore it, refuse it, or drop the link.</summary>
internal readonly record struct CommandFault(bool Ignore, int? RefuseCode, bool Disconnect);

/// <summary>What to do with an outgoing reply: send it, drop it, invert one byte, send it late.</summary>
internal readonly record struct ReplyFault(bool Drop, int? CorruptByte, TimeSpan Delay);
